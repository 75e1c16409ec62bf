//! Parameters given outside the scene file (a command line, a render job),
//! layered over the file's as pbrt-v4 layers its options: an override
//! replaces the file's parameter of the same name, or adds it, and is then
//! read by the same typed getters and reported by the same unused-parameter
//! check as the file's. Each override is parsed as scene text in a "file"
//! of its own, named by its origin (e.g. the flag that gave it), so its
//! errors and warnings point at it with a line, column and caret.

use crate::desc::Entity;
use crate::lexer::tokenize;
use crate::loc::{Diagnostic, Loc, SourceFile};
use crate::params::ParamSet;
use serde::{Deserialize, Serialize};

/// One override of a directive's entity (`Film`, `Sampler`, `Integrator`,
/// `PixelFilter`): a new type, parameters, or both.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Override {
    pub directive: String,
    /// A new type for the entity, e.g. `photon` for `Integrator`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ty: Option<String>,
    /// Parameters in scene-file syntax, e.g. `"integer photons" [ 20000 ]`.
    #[serde(default, skip_serializing_if = "String::is_empty")]
    pub params: String,
    /// Where it came from, for diagnostics (the name of its "file").
    pub origin: String,
}

/// Overrides in the order they were given (a later one wins).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(transparent)]
pub struct Overrides {
    pub items: Vec<Override>,
}

impl Overrides {
    /// Adds parameter `decl` (`"integer photons"`) with `value` as scene text
    /// (`20000`, `"mis"`, `[0 1 0 1]`).
    pub fn param(&mut self, directive: &str, decl: &str, value: &str, origin: &str) {
        self.items.push(Override {
            directive: directive.into(),
            ty: None,
            params: format!("\"{decl}\" [ {value} ]"),
            origin: origin.into(),
        });
    }

    /// Sets the entity's type.
    pub fn set_type(&mut self, directive: &str, ty: &str, origin: &str) {
        self.items.push(Override {
            directive: directive.into(),
            ty: Some(ty.into()),
            params: String::new(),
            origin: origin.into(),
        });
    }

    /// Film resolution: `xresolution` and `yresolution`.
    pub fn resolution(&mut self, w: u32, h: u32) -> &mut Self {
        self.resolution_from(w, h, "override")
    }
    pub fn resolution_from(&mut self, w: u32, h: u32, origin: &str) -> &mut Self {
        self.param("Film", "integer xresolution", &w.to_string(), origin);
        self.param("Film", "integer yresolution", &h.to_string(), origin);
        self
    }

    /// Film `cropwindow` (fractions x0 x1 y0 y1).
    pub fn crop_from(&mut self, c: [f32; 4], origin: &str) -> &mut Self {
        let v = format!("{} {} {} {}", c[0], c[1], c[2], c[3]);
        self.param("Film", "float cropwindow", &v, origin);
        self
    }

    /// Sampler `pixelsamples`.
    pub fn spp(&mut self, n: u32) -> &mut Self {
        self.spp_from(n, "override")
    }
    pub fn spp_from(&mut self, n: u32, origin: &str) -> &mut Self {
        self.param("Sampler", "integer pixelsamples", &n.to_string(), origin);
        self
    }

    /// PixelFilter `splat` (lumis' own): splat the samples (true) or
    /// sample the filter (false).
    pub fn filter_splat(&mut self, splat: bool) -> &mut Self {
        self.filter_splat_from(splat, "override")
    }
    pub fn filter_splat_from(&mut self, splat: bool, origin: &str) -> &mut Self {
        self.param("PixelFilter", "bool splat", &splat.to_string(), origin);
        self
    }

    /// The sampler type.
    pub fn sampler(&mut self, ty: &str) -> &mut Self {
        self.sampler_from(ty, "override")
    }
    pub fn sampler_from(&mut self, ty: &str, origin: &str) -> &mut Self {
        self.set_type("Sampler", ty, origin);
        self
    }

    /// The integrator type.
    pub fn integrator(&mut self, ty: &str) -> &mut Self {
        self.integrator_from(ty, "override")
    }
    pub fn integrator_from(&mut self, ty: &str, origin: &str) -> &mut Self {
        self.set_type("Integrator", ty, origin);
        self
    }

    /// Integrator `maxdepth`.
    pub fn max_depth(&mut self, d: u32) -> &mut Self {
        self.max_depth_from(d, "override")
    }
    pub fn max_depth_from(&mut self, d: u32, origin: &str) -> &mut Self {
        self.param("Integrator", "integer maxdepth", &d.to_string(), origin);
        self
    }

    /// Any integrator parameter, e.g. `("integer photons", "20000")` or
    /// `("string caustics", "\"mis\"")`.
    pub fn integrator_param(&mut self, decl: &str, value: &str) -> &mut Self {
        self.param("Integrator", decl, value, "override");
        self
    }

    /// The type `directive` is overridden to, with where it was given.
    pub fn type_of(&self, directive: &str) -> Option<(&str, &str)> {
        self.items
            .iter()
            .rev()
            .filter(|o| o.directive == directive)
            .find_map(|o| o.ty.as_deref().map(|t| (t, o.origin.as_str())))
    }

    pub fn is_empty(&self) -> bool {
        self.items.is_empty()
    }

    /// Whether an override sets parameter `name` of `directive`.
    pub fn sets(&self, directive: &str, name: &str) -> bool {
        let decl_end = format!(" {name}\"");
        self.items
            .iter()
            .any(|o| o.directive == directive && o.params.contains(&decl_end))
    }

    /// `entity` (the file's, if any) with this set's overrides of
    /// `directive` layered on; without a file entity, one of type
    /// `default_ty` is made when there is anything to layer.
    pub fn apply(
        &self,
        directive: &str,
        entity: Option<&Entity>,
        default_ty: &str,
    ) -> Result<Option<Entity>, Diagnostic> {
        let mut out = entity.cloned();
        for o in self.items.iter().filter(|o| o.directive == directive) {
            let file = SourceFile::new(o.origin.clone(), o.params.clone());
            let here = Loc {
                file: file.clone(),
                line: 1,
                col: 1,
                len: o.params.chars().count().max(1) as u32,
            };
            let e = out.get_or_insert_with(|| Entity {
                ty: default_ty.into(),
                params: ParamSet::new(),
                loc: here.clone(),
            });
            if let Some(ty) = &o.ty {
                e.ty = ty.clone();
                e.loc = here;
            }
            if !o.params.is_empty() {
                for p in ParamSet::parse(&tokenize(&file)?)?.params {
                    e.params.params.retain(|q| q.name != p.name);
                    e.params.push(p);
                }
            }
        }
        Ok(out)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn file_entity() -> Entity {
        let f = SourceFile::new("a.pbrt", "\"integer maxdepth\" 5 \"integer photons\" 10");
        Entity {
            ty: "photon".into(),
            params: ParamSet::parse(&tokenize(&f).unwrap()).unwrap(),
            loc: Loc::none(),
        }
    }

    #[test]
    fn overrides_replace_and_add_and_keep_their_origin() {
        let mut o = Overrides::default();
        o.param("Integrator", "integer photons", "99", "--photons");
        o.param("Integrator", "string caustics", "\"gather\"", "--caustics");
        o.param("Film", "integer xresolution", "7", "--resolution");
        let e = o
            .apply("Integrator", Some(&file_entity()), "path")
            .unwrap()
            .unwrap();
        assert_eq!(e.ty, "photon");
        assert_eq!(e.params.get_int("maxdepth", 0).unwrap(), 5);
        assert_eq!(e.params.get_int("photons", 0).unwrap(), 99);
        assert_eq!(e.params.get_string("caustics", "mis").unwrap(), "gather");
        assert_eq!(e.params.params.len(), 3);
        assert_eq!(e.params.loc_of("photons").unwrap().file.path, "--photons");
        assert!(o.sets("Integrator", "photons") && o.sets("Film", "xresolution"));
        assert!(!o.sets("Integrator", "maxdepth") && !o.sets("Film", "photons"));
        // A directive the file lacks gets an entity of the default type.
        let f = o.apply("Film", None, "rgb").unwrap().unwrap();
        assert_eq!(
            (f.ty.as_str(), f.params.get_int("xresolution", 0).unwrap()),
            ("rgb", 7)
        );
        assert!(o.apply("Sampler", None, "zsobol").unwrap().is_none());
    }

    #[test]
    fn type_overrides_and_bad_values_are_located() {
        let mut o = Overrides::default();
        o.set_type("Integrator", "path", "--integrator");
        let e = o
            .apply("Integrator", Some(&file_entity()), "path")
            .unwrap()
            .unwrap();
        assert_eq!(e.ty, "path");
        assert_eq!(e.loc.file.path, "--integrator");
        assert_eq!(o.type_of("Integrator"), Some(("path", "--integrator")));
        let mut bad = Overrides::default();
        bad.param("Integrator", "integer photons", "\"many\"", "--photons");
        let err = bad
            .apply("Integrator", None, "path")
            .unwrap_err()
            .to_string();
        assert!(err.contains("--photons:1:"), "{err}");
    }

    #[test]
    fn round_trips_through_json() {
        let mut o = Overrides::default();
        o.set_type("Sampler", "independent", "--sampler");
        o.param("Sampler", "integer pixelsamples", "4", "--spp");
        let back: Overrides = serde_json::from_str(&serde_json::to_string(&o).unwrap()).unwrap();
        assert_eq!(back, o);
    }
}
