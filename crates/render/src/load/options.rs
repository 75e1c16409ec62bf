//! Camera, film, sampler, pixel filter and integrator options.

use super::Warnings;
use crate::camera::Camera;
use crate::film::{Filter, PixelBounds};
use crate::integrator::bdpt::BdptSettings;
use crate::integrator::vcm::VcmSettings;
use crate::integrator::{Integrator, RenderSettings};
use lumis_math::{Mat3, SamplerKind, Transform, Vec2, Vec3};
use lumis_scene::{Diagnostic, Entity, Loc, Overrides, SceneDesc};

/// Everything the scene file says about how to render it.
#[derive(Clone, Debug)]
pub struct RenderOptions {
    pub resolution: (u32, u32),
    pub crop: PixelBounds,
    pub spp: u32,
    pub sampler: SamplerKind,
    pub filter: Filter,
    pub integrator: Integrator,
    /// Output file name from the Film, if any.
    pub filename: Option<String>,
    /// Film sensor scale: `iso / 100 * exposuretime` (pbrt-v4's imaging ratio).
    pub imaging_scale: f32,
    /// Film `whitebalance` (kelvin) as a matrix on linear sRGB
    /// (`lumis_math::spectrum::white_balance`); `None` without one.
    pub white_balance: Option<Mat3>,
}

impl RenderOptions {
    /// Render settings for these options: `spp` samples per pixel (0 with a
    /// time limit: unbounded), one sample per pass, no clamp, no time limit.
    pub fn render_settings(&self, spp: u32, seed: u64, threads: usize) -> RenderSettings {
        RenderSettings {
            spp,
            seed,
            threads,
            time_limit: None,
            sampler: self.sampler,
            filter: self.filter.clone(),
            crop: self.crop,
            spp_per_pass: 1,
            clamp: None,
            inject_nan: None,
            passes: None,
        }
    }

    /// The film's output of interleaved linear RGB: the imaging ratio, then
    /// the white balance (both linear, so applying them to the finished
    /// image equals pbrt-v4's applying them per sample).
    pub fn to_output(scale: f32, white_balance: Option<Mat3>, rgb: &mut [f32]) {
        for px in rgb.chunks_exact_mut(3) {
            let mut v = Vec3::new(px[0], px[1], px[2]) * scale;
            if let Some(m) = white_balance {
                v = m * v;
            }
            px.copy_from_slice(&v.to_array());
        }
    }
}

pub use crate::film::MAX_PIXELS;

pub fn check_resolution(res: (u32, u32), loc: &Loc) -> Result<(), Diagnostic> {
    if res.0 == 0 || res.1 == 0 || res.0 as u64 * res.1 as u64 > MAX_PIXELS {
        return Err(Diagnostic::error(
            loc,
            format!(
                "film resolution {}x{} is out of range (at least 1x1, at most {} pixels)",
                res.0, res.1, MAX_PIXELS
            ),
        ));
    }
    Ok(())
}

/// The scene's options with `ov` layered over the file's `Film`, `Sampler`,
/// `PixelFilter` and `Integrator` parameters.
pub fn build_options(
    desc: &SceneDesc,
    ov: &Overrides,
    w: &mut Warnings,
) -> Result<RenderOptions, Diagnostic> {
    let mut resolution = (1280u32, 720u32);
    let mut crop = [0.0f32, 1.0, 0.0, 1.0];
    let mut filename = None;
    let mut imaging_scale = 1.0;
    let mut white_balance = None;
    let mut film_loc = Loc::none();
    if let Some(f) = &ov.apply("Film", desc.film.as_ref(), "rgb")? {
        film_loc = f.loc.clone();
        if !matches!(f.ty.as_str(), "rgb") {
            w.push(Diagnostic::warning(
                &f.loc,
                format!("film type `{}` is not supported yet; using `rgb`", f.ty),
            ));
        }
        let p = &f.params;
        let xr = p.get_int("xresolution", 1280)?;
        let yr = p.get_int("yresolution", 720)?;
        if xr <= 0 || yr <= 0 {
            return Err(Diagnostic::error(
                &f.loc,
                format!("film resolution {xr}x{yr} must be positive"),
            ));
        }
        resolution = (xr as u32, yr as u32);
        if let Some(c) = p.get_floats("cropwindow")? {
            if c.len() != 4 {
                return Err(Diagnostic::error(
                    &p.loc_of("cropwindow").unwrap(),
                    "cropwindow needs 4 values: x0 x1 y0 y1",
                ));
            }
            crop = [
                c[0].clamp(0.0, 1.0),
                c[1].clamp(0.0, 1.0),
                c[2].clamp(0.0, 1.0),
                c[3].clamp(0.0, 1.0),
            ];
        }
        filename = p.get_opt_string("filename")?;
        let iso = p.get_float("iso", 100.0)?;
        let exposure = p.get_float("exposuretime", 1.0)?;
        imaging_scale = iso / 100.0 * exposure;
        let wb = p.get_float("whitebalance", 0.0)?;
        if wb != 0.0 {
            if !(wb > 0.0) {
                return Err(Diagnostic::error(
                    &p.loc_of("whitebalance").unwrap_or_else(|| f.loc.clone()),
                    format!("whitebalance must be a positive temperature in kelvin, found {wb}"),
                ));
            }
            white_balance = Some(lumis_math::spectrum::white_balance(wb as f64));
        }
        // Camera sensors (measured response curves) are not modelled.
        let mut ignored = vec!["savefp16", "diagonal", "maxcomponentvalue"];
        if p.get_string("sensor", "cie1931")? != "cie1931" {
            ignored.push("sensor");
        }
        w.unsupported(p, &ignored, "film", "ignored");
        w.unused(
            p,
            "film \"rgb\"",
            &[
                "xresolution",
                "yresolution",
                "cropwindow",
                "filename",
                "iso",
                "exposuretime",
                "whitebalance",
                "sensor",
            ],
        );
    }
    check_resolution(resolution, &film_loc)?;
    let crop = crop_bounds(resolution, crop);
    if crop.area() == 0 {
        return Err(Diagnostic::error(
            &film_loc,
            "the crop window covers no pixel",
        ));
    }

    let (mut spp, mut sampler) = (16u32, SamplerKind::Sobol);
    if let Some((ty, origin)) = ov.type_of("Sampler") {
        if !SAMPLERS.contains(&ty) {
            return Err(
                Diagnostic::plain_error(format!("unknown sampler `{ty}` ({origin})"))
                    .with_help(format!("available: {}", SAMPLERS.join(", "))),
            );
        }
    }
    if let Some(s) = &ov.apply("Sampler", desc.sampler.as_ref(), "zsobol")? {
        spp = s.params.get_int("pixelsamples", 16)?.max(1) as u32;
        s.params.mark_used("seed");
        sampler = match s.ty.as_str() {
            "independent" => SamplerKind::Independent,
            "sobol" | "zsobol" | "paddedsobol" => SamplerKind::Sobol,
            other => {
                w.push(Diagnostic::warning(
                    &s.loc,
                    format!("sampler `{other}` is not available; using Owen-scrambled Sobol"),
                ));
                for p in ["randomization", "jitter", "xsamples", "ysamples"] {
                    s.params.mark_used(p);
                }
                SamplerKind::Sobol
            }
        };
        w.unused(
            &s.params,
            &format!("sampler \"{}\"", s.ty),
            &["pixelsamples", "seed", "randomization"],
        );
    }

    let filter = match &ov.apply("PixelFilter", desc.filter.as_ref(), "gaussian")? {
        None => {
            let mut f = Filter::gaussian(Vec2::splat(1.5), 0.5);
            f.splat = splats_by_default(&f);
            f
        }
        Some(f) => build_filter(f, w)?,
    };

    let integrator = build_integrator(desc, ov, w)?;
    if let Some(p) = integrator.photon().and_then(|s| s.progressive) {
        spp = progressive_spp(spp, p, ov)?;
    }
    Ok(RenderOptions {
        resolution,
        crop,
        spp,
        sampler,
        filter,
        integrator,
        filename,
        imaging_scale,
        white_balance,
    })
}

/// The progressive mode's sample count: `iterations` x `iterationspp` when
/// the iteration count is given, unless only the scene file gives it and
/// an override gives the sample count (a command line wins over the file);
/// both given by overrides is an error.
fn progressive_spp(
    spp: u32,
    p: crate::integrator::photon::Progressive,
    ov: &Overrides,
) -> Result<u32, Diagnostic> {
    if p.iterations == 0 {
        return Ok(spp);
    }
    let (iters_ov, spp_ov) = (
        ov.sets("Integrator", "iterations"),
        ov.sets("Sampler", "pixelsamples"),
    );
    if iters_ov && spp_ov {
        return Err(Diagnostic::plain_error(
            "both the iteration count and the sample count are given; give one",
        ));
    }
    if spp_ov {
        return Ok(spp);
    }
    Ok(p.iterations.saturating_mul(p.iteration_spp.max(1)))
}

/// Sampler types a scene file or an override may name without a warning.
const SAMPLERS: &[&str] = &["independent", "sobol", "zsobol", "paddedsobol"];

/// The file's `Integrator` with the overrides layered on. pbrt-v4's other
/// integrators are located warnings: `sppm` renders with `photon` (its
/// scenes are caustic scenes), the rest with `path`.
fn build_integrator(
    desc: &SceneDesc,
    ov: &Overrides,
    w: &mut Warnings,
) -> Result<Integrator, Diagnostic> {
    let mut file = desc.integrator.clone();
    if let Some(e) = &mut file {
        if e.ty == "volpath" {
            // pbrt-v4's volumetric path tracer is lumis' `path`, which
            // renders media; its light sampler choice is ignored below.
            e.ty = "path".into();
        }
        if !Integrator::NAMES.contains(&e.ty.as_str()) {
            let fallback = if e.ty == "sppm" {
                // The scenes written for SPPM are caustic scenes: render them
                // with the photon method rather than a path tracer that
                // cannot see caustics of delta lights.
                w.push(Diagnostic::warning(
                    &e.loc,
                    "integrator `sppm` is not available; using `photon` (photon mapping \
                     with final gathering) with its own defaults",
                ));
                "photon"
            } else {
                let note = match e.ty.as_str() {
                    "mlt" => "it is not implemented",
                    _ => "it is not a lumis integrator",
                };
                w.push(Diagnostic::warning(
                    &e.loc,
                    format!(
                        "integrator `{}` is not available ({note}); using `path`",
                        e.ty
                    ),
                ));
                "path"
            };
            for p in e.params.unused() {
                if p.name != "maxdepth" {
                    p.mark_used();
                }
            }
            e.ty = fallback.into();
        }
        for ignored in ["lightsampler", "regularize"] {
            e.params.mark_used(ignored);
        }
    }
    if let Some((ty, origin)) = ov.type_of("Integrator") {
        // The file's parameters were written for its own integrator.
        if let Some(e) = file.as_ref().filter(|e| e.ty != ty) {
            for p in e.params.unused() {
                if p.name != "maxdepth" {
                    p.mark_used();
                }
            }
        }
        if !Integrator::NAMES.contains(&ty) {
            return Err(
                Diagnostic::plain_error(format!("unknown integrator `{ty}` ({origin})"))
                    .with_help(format!("available: {}", Integrator::NAMES.join(", "))),
            );
        }
    }
    let Some(e) = ov.apply("Integrator", file.as_ref(), "path")? else {
        return Ok(Integrator::Path { max_depth: 5 });
    };
    let max_depth = e.params.get_int("maxdepth", 5)?.max(0) as u32;
    let integrator = match e.ty.as_str() {
        "photon" => Integrator::Photon(super::photon::photon_settings(&e, max_depth)?),
        "bdpt" => Integrator::Bdpt(bdpt_settings(&e, max_depth)?),
        "vcm" => Integrator::Vcm(vcm_settings(&e, max_depth)?),
        name => Integrator::from_name(name, max_depth).expect("a checked integrator name"),
    };
    let mut known = vec!["maxdepth"];
    if e.ty == "bdpt" {
        known.extend(crate::integrator::bdpt::PARAMS.iter().map(|p| p.name));
    }
    if e.ty == "vcm" {
        known.extend(crate::integrator::vcm::PARAMS.iter().map(|p| p.name));
    }
    if e.ty == "photon" {
        known.extend(super::photon::names());
        if integrator.photon().is_some_and(|s| s.progressive.is_none()) {
            // Read only by the progressive mode: say so rather than drop them.
            for name in PROGRESSIVE_ONLY {
                if let Some(loc) = e.params.loc_of(name) {
                    e.params.mark_used(name);
                    w.push(Diagnostic::warning(
                        &loc,
                        format!("`{name}` has no effect with `\"bool progressive\" false`"),
                    ));
                }
            }
        }
        let share_ignored = integrator
            .photon()
            .and_then(|s| s.progressive)
            .is_some_and(|p| p.photon_share == 0.0);
        if let Some(loc) = e.params.loc_of("photonshare").filter(|_| share_ignored) {
            let share = e.params.get_float("photonshare", 0.0)?;
            if share > 0.0 {
                w.push(Diagnostic::warning(
                    &loc,
                    "`photonshare` has no effect when `photons` or `causticphotons` is given",
                ));
            }
        }
    }
    w.unused(&e.params, &format!("integrator \"{}\"", e.ty), &known);
    Ok(integrator)
}

/// `bdpt`'s settings: `strategy` [s t] renders one strategy alone, `mis`
/// weights them (the default).
fn bdpt_settings(e: &Entity, max_depth: u32) -> Result<BdptSettings, Diagnostic> {
    let p = &e.params;
    let mut st = BdptSettings::new(max_depth);
    st.mis = p.get_bool("mis", true)?;
    if let Some(loc) = p.loc_of("strategy") {
        let v = p.get_ints("strategy")?.unwrap_or_default();
        match v[..] {
            [s, t] if s >= 0 && t >= 1 => st.strategy = Some((s as u32, t as u32)),
            _ => {
                return Err(Diagnostic::error(
                    &loc,
                    format!("`strategy` must be two integers S >= 0 and T >= 1, found {v:?}"),
                ))
            }
        }
    }
    Ok(st)
}

/// `vcm`'s settings: the first radius (0: automatic) and the sequence's `a`.
fn vcm_settings(e: &Entity, max_depth: u32) -> Result<VcmSettings, Diagnostic> {
    let p = &e.params;
    let mut st = VcmSettings::new(max_depth);
    st.initial_radius = p.get_float("initialradius", st.initial_radius)?;
    st.shrink = p.get_float("shrink", st.shrink)?;
    let bad = |name: &str, what: &str, v: f32| -> Result<(), Diagnostic> {
        let loc = p
            .loc_of(name)
            .expect("a value read from the file or a flag");
        Err(Diagnostic::error(
            &loc,
            format!("`{name}` must be {what}, found {v}"),
        ))
    };
    if !(st.initial_radius >= 0.0 && st.initial_radius.is_finite()) {
        bad("initialradius", "a finite number >= 0", st.initial_radius)?;
    }
    if !(st.shrink > 0.0 && st.shrink <= 1.0) {
        bad("shrink", "in (0, 1]", st.shrink)?;
    }
    Ok(st)
}

/// Parameters of `photon` that only the progressive mode reads.
const PROGRESSIVE_ONLY: [&str; 5] = [
    "iterationspp",
    "shrink",
    "initialradius",
    "iterations",
    "photonshare",
];

/// pbrt's crop window (fractions) to pixel bounds.
pub fn crop_bounds(res: (u32, u32), c: [f32; 4]) -> PixelBounds {
    let f = |v: f32, n: u32| ((v * n as f32).ceil() as u32).min(n);
    PixelBounds {
        x0: f(c[0], res.0),
        x1: f(c[1], res.0),
        y0: f(c[2], res.1),
        y1: f(c[3], res.1),
    }
}

/// The largest radius (pixels) of a filter that splats.
const MAX_SPLAT_RADIUS: f32 = 16.0;

/// Whether a filter splats when its file does not say: when it reaches
/// past its own pixel (a box of radius 1/2 gives the same image either way)
/// and no further than a splat may.
fn splats_by_default(f: &Filter) -> bool {
    f.reach() != (0, 0) && f.radius.max_element() <= MAX_SPLAT_RADIUS
}

fn build_filter(f: &Entity, w: &mut Warnings) -> Result<Filter, Diagnostic> {
    let p = &f.params;
    let radius = |d: f32| -> Result<Vec2, Diagnostic> {
        Ok(Vec2::new(
            p.get_float("xradius", d)?,
            p.get_float("yradius", d)?,
        ))
    };
    let filter = match f.ty.as_str() {
        "box" => Filter::boxf(radius(0.5)?),
        "triangle" => Filter::triangle(radius(2.0)?),
        "gaussian" => {
            let r = radius(1.5)?;
            Filter::gaussian(r, p.get_float("sigma", 0.5)?)
        }
        other => {
            for q in ["xradius", "yradius", "B", "C", "tau"] {
                p.mark_used(q);
            }
            w.push(Diagnostic::warning(
                &f.loc,
                format!("pixel filter `{other}` is not available (negative lobes); using gaussian"),
            ));
            Filter::gaussian(Vec2::splat(1.5), 0.5)
        }
    };
    if !(filter.radius.x > 0.0 && filter.radius.y > 0.0) {
        return Err(Diagnostic::error(&f.loc, "filter radius must be positive"));
    }
    let mut filter = filter;
    filter.splat = p.get_bool("splat", splats_by_default(&filter))?;
    // A splatted sample is kept for every pixel it reaches until they all
    // have it (`integrator/splatted.rs`): memory grows with the radius.
    if filter.splat && filter.radius.max_element() > MAX_SPLAT_RADIUS {
        let loc = p
            .loc_of("xradius")
            .or(p.loc_of("yradius"))
            .unwrap_or(f.loc.clone());
        return Err(Diagnostic::error(
            &loc,
            format!(
                "a splatting filter's radius must be at most {MAX_SPLAT_RADIUS} pixels, not {}",
                filter.radius.max_element()
            ),
        ));
    }
    w.unused(
        p,
        &format!("filter \"{}\"", f.ty),
        &["xradius", "yradius", "sigma", "splat"],
    );
    Ok(filter)
}

pub fn build_camera(
    desc: &SceneDesc,
    o: &RenderOptions,
    w: &mut Warnings,
) -> Result<Camera, Diagnostic> {
    let Some(c) = &desc.camera else {
        w.push(Diagnostic::plain_error("no `Camera` in the scene; using a perspective camera at the origin looking down +z").into_warning());
        return Ok(Camera::perspective(
            Transform::IDENTITY,
            o.resolution,
            90.0,
            0.0,
            1e6,
        ));
    };
    let world_from_camera = c.camera_from_world.inverse();
    let p = &c.entity.params;
    if c.entity.ty != "perspective" {
        w.push(Diagnostic::warning(
            &c.entity.loc,
            format!(
                "camera `{}` is not supported yet; using perspective",
                c.entity.ty
            ),
        ));
    }
    let fov = p.get_float("fov", 90.0)?;
    if !(fov > 0.0 && fov < 180.0) {
        return Err(Diagnostic::error(
            &p.loc_of("fov").unwrap_or(c.entity.loc.clone()),
            format!("fov {fov} must be between 0 and 180 degrees"),
        ));
    }
    let lens = p.get_float("lensradius", 0.0)?;
    let focal = p.get_float("focaldistance", 1e6)?;
    let mut cam = Camera::perspective(world_from_camera, o.resolution, fov, lens, focal);
    if let Some(sw) = p.get_floats("screenwindow")? {
        if sw.len() == 4 {
            cam.screen = [sw[0], sw[1], sw[2], sw[3]];
        }
    }
    if p.has("frameaspectratio") {
        let fa = p.get_float("frameaspectratio", 1.0)?;
        cam.screen = if fa > 1.0 {
            [-fa, fa, -1.0, 1.0]
        } else {
            [-1.0, 1.0, -1.0 / fa, 1.0 / fa]
        };
    }
    for q in ["shutteropen", "shutterclose"] {
        p.mark_used(q);
    }
    w.unused(
        p,
        "camera \"perspective\"",
        &[
            "fov",
            "lensradius",
            "focaldistance",
            "screenwindow",
            "frameaspectratio",
        ],
    );
    Ok(cam)
}

use super::IntoWarning;
