//! The scene file's `Integrator`: lumis' own, pbrt-v4's others as located
//! warnings with the fallback they get, and the command line winning.

use lumis_render::integrator::Integrator;
use lumis_render::load::{load_text, LoadedScene, Overrides};
use std::path::Path;

fn load(integrator: &str, ov: &Overrides) -> LoadedScene {
    let text = format!(
        "{integrator}\nFilm \"rgb\" \"integer xresolution\" [ 8 ] \"integer yresolution\" [ 8 ]\n\
         Camera \"perspective\"\nWorldBegin\nLightSource \"point\" \"rgb I\" [1 1 1]\n\
         Shape \"sphere\"\n"
    );
    load_text(&text, "s.pbrt", Path::new("."), ov).unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn sppm_scenes_render_with_photon() {
    let l = load(
        r#"Integrator "sppm" "integer maxdepth" 7 "float radius" 0.1
           "integer photonsperiteration" 100000 "integer seed" 3"#,
        &Overrides::default(),
    );
    let i = &l.options.integrator;
    assert_eq!((i.name(), i.max_depth()), ("photon", 7));
    // The photon method's own defaults, sized by its depth.
    assert_eq!(i.photon().unwrap().max_depth, 7);
    // One warning, located, and none about SPPM's parameters.
    assert_eq!(l.warnings.len(), 1, "{:?}", l.warnings);
    let w = &l.warnings[0];
    assert!(w.message.contains("using `photon`"), "{w}");
    assert!(w.to_string().contains("s.pbrt:1:"), "{w}");
}

#[test]
fn other_pbrt_integrators_fall_back_to_path() {
    let l = load(
        r#"Integrator "mlt" "integer maxdepth" 4"#,
        &Overrides::default(),
    );
    assert_eq!(l.options.integrator, Integrator::Path { max_depth: 4 });
    assert_eq!(l.warnings.len(), 1, "{:?}", l.warnings);
    assert!(l.warnings[0].message.contains("using `path`"));
}

#[test]
fn pbrt_volpath_is_path() {
    let l = load(
        r#"Integrator "volpath" "integer maxdepth" 4 "string lightsampler" "bvh" "bool regularize" false"#,
        &Overrides::default(),
    );
    assert_eq!(l.options.integrator, Integrator::Path { max_depth: 4 });
    assert!(l.warnings.is_empty(), "{:?}", l.warnings);
}

#[test]
fn pbrt_bdpt_is_bdpt() {
    let l = load(
        r#"Integrator "bdpt" "integer maxdepth" 4 "bool regularize" false"#,
        &Overrides::default(),
    );
    assert_eq!(
        l.options.integrator,
        Integrator::Bdpt(lumis_render::integrator::bdpt::BdptSettings::new(4))
    );
    assert!(l.warnings.is_empty(), "{:?}", l.warnings);
}

/// `strategy` must name one (s, t): two integers, t at least 1.
#[test]
fn bdpt_strategy_out_of_range_is_a_located_error() {
    let text =
        "Integrator \"bdpt\" \"integer strategy\" [ 2 0 ]\nCamera \"perspective\"\nWorldBegin\n";
    let e = match load_text(text, "s.pbrt", Path::new("."), &Overrides::default()) {
        Ok(_) => panic!("accepted"),
        Err(e) => e.to_string(),
    };
    assert!(e.contains("s.pbrt:1:"), "{e}");
    assert!(e.contains("`strategy` must be two integers"), "{e}");
}

#[test]
fn vcm_reads_its_radius_and_shrink() {
    let l = load(
        r#"Integrator "vcm" "integer maxdepth" 7 "float initialradius" 0.02 "float shrink" 0.5"#,
        &Overrides::default(),
    );
    let mut st = lumis_render::integrator::vcm::VcmSettings::new(7);
    st.initial_radius = 0.02;
    st.shrink = 0.5;
    assert_eq!(l.options.integrator, Integrator::Vcm(st));
    assert!(l.warnings.is_empty(), "{:?}", l.warnings);
    assert_eq!(
        Integrator::from_name("vcm", 5),
        Some(Integrator::Vcm(
            lumis_render::integrator::vcm::VcmSettings::new(5)
        ))
    );
}

/// `shrink` must be in (0, 1] and `initialradius` at least 0.
#[test]
fn vcm_bad_shrink_or_radius_is_a_located_error() {
    for (param, what) in [
        (r#""float shrink" 0"#, "`shrink` must be in (0, 1]"),
        (r#""float shrink" 1.5"#, "`shrink` must be in (0, 1]"),
        (
            r#""float initialradius" -1"#,
            "`initialradius` must be a finite number >= 0",
        ),
    ] {
        let text = format!("Integrator \"vcm\" {param}\nCamera \"perspective\"\nWorldBegin\n");
        let e = match load_text(&text, "s.pbrt", Path::new("."), &Overrides::default()) {
            Ok(_) => panic!("{param}: accepted"),
            Err(e) => e.to_string(),
        };
        assert!(e.contains("s.pbrt:1:"), "{e}");
        assert!(e.contains(what), "{e}");
    }
}

#[test]
fn pbrt_lightpath_is_the_light_tracer() {
    let l = load(
        r#"Integrator "lightpath" "integer maxdepth" 4"#,
        &Overrides::default(),
    );
    assert_eq!(
        l.options.integrator,
        Integrator::LightTracer { max_depth: 4 }
    );
    assert!(l.warnings.is_empty(), "{:?}", l.warnings);
}

#[test]
fn command_line_integrator_wins() {
    let mut ov = Overrides::default();
    ov.integrator("direct");
    let l = load(r#"Integrator "sppm""#, &ov);
    assert!(matches!(l.options.integrator, Integrator::Direct { .. }));
}
