//! Second stage of input: the plain [`SceneDesc`] from `lumis-scene` becomes
//! checked runtime objects. Unknown parameters become warnings with their
//! locations; unsupported types are warnings too, never silently ignored.
//!
//! The top layer of the crate: it builds every runtime object, so it may
//! use any module; the other modules do not import it (one known exception
//! is listed in `tests/layers`).

mod area_lights;
mod envmap;
mod inputs;
mod lights;
mod material;
mod medium;
mod medium_presets;
pub mod options;
pub mod photon;
mod shape;
mod spectrum;
mod texture;

pub use inputs::inputs_hash;
pub use lumis_scene::Inputs;
pub use options::RenderOptions;

use crate::scene::{Scene, Shapes};
use lumis_scene::{Diagnostic, SceneDesc};
use std::path::Path;

/// A scene ready to render, its options from the file, and the warnings.
pub struct LoadedScene {
    pub scene: Scene,
    pub options: RenderOptions,
    pub warnings: Vec<Diagnostic>,
    /// The text and every file it was built from (see [`inputs_hash`]).
    pub inputs: Inputs,
}

/// Collects warnings during the build.
#[derive(Default)]
pub struct Warnings(pub Vec<Diagnostic>);

impl Warnings {
    pub fn push(&mut self, d: Diagnostic) {
        self.0.push(d);
    }
    pub fn unused(&mut self, params: &lumis_scene::ParamSet, context: &str, known: &[&str]) {
        self.0.extend(params.report_unused(context, known));
    }
    /// Each of `names` that is present: consumed, with a warning at its
    /// location that `context` does not support it yet (`note` says what happens instead).
    pub fn unsupported(
        &mut self,
        params: &lumis_scene::ParamSet,
        names: &[&str],
        context: &str,
        note: &str,
    ) {
        for &name in names {
            if let Some(loc) = params.loc_of(name) {
                params.mark_used(name);
                self.push(Diagnostic::warning(
                    &loc,
                    format!("{context} parameter `{name}` is not supported yet; {note}"),
                ));
            }
        }
    }
}

/// Values that win over the scene file's (a command line's, a job's),
/// layered over its parameters by [`options::build_options`].
pub use lumis_scene::Overrides;

/// The built-in default scene (also shipped as `scenes/default.pbrt`).
pub const DEFAULT_SCENE: &str = include_str!("../../../../scenes/default.pbrt");

/// Parses and builds a scene file.
pub fn load_path(path: &Path, ov: &Overrides) -> Result<LoadedScene, Diagnostic> {
    let desc = lumis_scene::load_file(path)?;
    build_scene(&desc, ov)
}

/// Parses and builds scene text (`name` labels diagnostics; paths resolve against `base_dir`).
pub fn load_text(
    text: &str,
    name: &str,
    base_dir: &Path,
    ov: &Overrides,
) -> Result<LoadedScene, Diagnostic> {
    let desc = lumis_scene::load_str(text, name, base_dir)?;
    build_scene(&desc, ov)
}

pub fn build_scene(desc: &SceneDesc, overrides: &Overrides) -> Result<LoadedScene, Diagnostic> {
    let mut w = Warnings(desc.warnings.clone());
    if !desc.saw_world_begin {
        return Err(Diagnostic::plain_error("the scene has no `WorldBegin`: nothing to render")
            .with_help("pbrt-v4 scenes put camera and film options first, then `WorldBegin`, then shapes and lights"));
    }
    let options = options::build_options(desc, overrides, &mut w)?;
    let camera = options::build_camera(desc, &options, &mut w)?;
    let mut tex = texture::build_textures(desc, &mut w)?;
    let mut materials = material::build_materials(desc, &mut tex, &mut w)?;
    let media = medium::build_media(desc, &mut w)?;
    let camera_medium = media.id(&desc.camera.as_ref().and_then(|c| c.medium.clone()))?;
    let mut shapes = Shapes::default();
    let mut lights = Vec::new();
    let mut surfaces = shape::Surfaces {
        mats: &mut materials,
        media: &media,
        tex: &tex,
        light_media: Vec::new(),
    };
    let (prims, instances) =
        shape::build_shapes(desc, &mut surfaces, &mut shapes, &mut lights, &mut w)?;
    let mut light_media = surfaces.light_media;
    lights::build_lights(desc, &media, &mut lights, &mut light_media, &mut w)?;
    debug_assert_eq!(light_media.len(), lights.len());
    if lights.is_empty() {
        w.push(
            Diagnostic::plain_error("the scene has no lights: the image will be black")
                .into_warning(),
        );
    }
    // Interface surfaces that do not change the medium cannot change the
    // image: they are left out (emitters stay).
    // Media are rendered by `path` only; other integrators leave them out
    // (with their boundaries), with a warning.
    let render_media = !media.media.is_empty()
        && matches!(
            options.integrator,
            crate::integrator::Integrator::Path { .. } | crate::integrator::Integrator::Photon(_)
        );
    let mut prims = prims;
    prims.retain(|p| {
        let m = &materials.materials[p.material as usize];
        p.light != crate::scene::NO_LIGHT
            || !m.is_interface()
            || (render_media && m.media.is_some())
    });
    if !render_media {
        // Nothing changes the medium where media are left out.
        for m in materials.materials.iter_mut() {
            m.media = None;
        }
    }
    let mut scene = Scene::with_instances(
        shapes,
        prims,
        instances,
        materials.materials,
        lights,
        camera,
    );
    if render_media {
        scene.media = media.media;
        scene.camera_medium = camera_medium;
        scene.light_media = light_media;
    } else if !media.media.is_empty() {
        let loc = desc
            .integrator
            .as_ref()
            .map_or_else(|| desc.media[0].entity.loc.clone(), |e| e.loc.clone());
        w.push(Diagnostic::warning(
            &loc,
            format!(
                "integrator `{}` does not render participating media yet (`path` and `photon` do): they are left out of this image",
                options.integrator.name()
            ),
        ).with_help("render media with `--integrator photon` or `--integrator path`"));
    }
    let mut textures = tex.textures;
    textures.footprint = crate::texture::Footprint::new(&scene.camera, options.spp);
    scene.textures = textures;
    Ok(LoadedScene {
        scene,
        options,
        warnings: w.0,
        inputs: desc.inputs(),
    })
}

trait IntoWarning {
    fn into_warning(self) -> Diagnostic;
}

impl IntoWarning for Diagnostic {
    fn into_warning(mut self) -> Diagnostic {
        self.severity = lumis_scene::Severity::Warning;
        self
    }
}
