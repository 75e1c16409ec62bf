//! The common scene mistakes, through the whole load (parse, then build):
//! each message says where, what was expected, and the nearest known name.

use lumis_render::load::{load_text, Overrides};
use lumis_scene::Diagnostic;
use std::path::Path;

const HEAD: &str = "Film \"rgb\" \"integer xresolution\" [ 8 ] \"integer yresolution\" [ 8 ]\nCamera \"perspective\"\n";

fn load(body: &str) -> Result<Vec<String>, String> {
    let text = format!("{HEAD}{body}");
    load_text(&text, "s.pbrt", Path::new("."), &Overrides::default())
        .map(|l| l.warnings.iter().map(Diagnostic::to_string).collect())
        .map_err(|e| e.to_string())
}

fn error(body: &str) -> String {
    match load(body) {
        Ok(w) => panic!("expected an error, loaded with warnings {w:?}"),
        Err(e) => e,
    }
}

#[test]
fn misspelled_parameter_warns_with_the_nearest_name() {
    let w = load("WorldBegin\nLightSource \"point\" \"rgb I\" [1 1 1]\nMaterial \"diffuse\" \"rgb reflectanse\" [0.5 0.5 0.5]\nShape \"sphere\"\n").unwrap();
    let w = w
        .iter()
        .find(|w| w.contains("reflectanse"))
        .expect("warning");
    assert!(
        w.starts_with("s.pbrt:5:20: warning: unknown parameter"),
        "{w}"
    );
    assert!(w.contains("did you mean `reflectance`?"), "{w}");
}

#[test]
fn wrong_parameter_type_says_what_was_expected() {
    let e = error("WorldBegin\nShape \"sphere\" \"string radius\" \"big\"\n");
    assert!(e.starts_with("s.pbrt:4:16: error:"), "{e}");
    assert!(
        e.contains("`radius`") && e.contains("`float`") && e.contains("`string`"),
        "{e}"
    );
}

#[test]
fn missing_world_begin_is_explained() {
    let e = error("");
    assert!(e.contains("no `WorldBegin`"), "{e}");
    assert!(
        e.contains("then `WorldBegin`, then shapes and lights"),
        "{e}"
    );
    // A shape before WorldBegin names the directive that was expected first.
    let e = error("Shape \"sphere\"\n");
    assert!(e.starts_with("s.pbrt:3:1: error:"), "{e}");
    assert!(e.contains("only allowed after WorldBegin"), "{e}");
}

#[test]
fn unknown_named_material_suggests_the_nearest_or_lists_the_defined() {
    let defs = "WorldBegin\nMakeNamedMaterial \"GlassBall\" \"string type\" \"dielectric\"\nMakeNamedMaterial \"Floor\" \"string type\" \"diffuse\"\n";
    let e = error(&format!(
        "{defs}NamedMaterial \"GlasBall\"\nShape \"sphere\"\n"
    ));
    assert!(e.starts_with("s.pbrt:6:"), "{e}");
    assert!(
        e.contains("named material `GlasBall` is not defined"),
        "{e}"
    );
    assert!(e.contains("did you mean `GlassBall`?"), "{e}");
    let e = error(&format!("{defs}NamedMaterial \"Wall\"\nShape \"sphere\"\n"));
    assert!(
        e.contains("named materials defined: Floor, GlassBall"),
        "{e}"
    );
}

#[test]
fn unbalanced_attribute_blocks_say_what_was_expected() {
    let e = error("WorldBegin\nAttributeEnd\n");
    assert!(e.starts_with("s.pbrt:4:1: error:"), "{e}");
    assert!(e.contains("no `AttributeBegin` is open"), "{e}");
    let e = error("WorldBegin\nAttributeBegin\nTransformEnd\n");
    assert!(e.contains("expected `AttributeEnd`"), "{e}");
    let w = load(
        "WorldBegin\nLightSource \"point\" \"rgb I\" [1 1 1]\nAttributeBegin\nShape \"sphere\"\n",
    )
    .unwrap();
    assert!(
        w.iter().any(|w| w.starts_with(
            "s.pbrt:5:1: warning: AttributeBegin has no matching AttributeEnd: expected it"
        )),
        "{w:?}"
    );
}

#[test]
fn photon_counts_out_of_range_are_located_errors() {
    let e = error("Integrator \"photon\" \"integer specularsplits\" [ 65 ]\nWorldBegin\n");
    assert!(e.starts_with("s.pbrt:3:"), "{e}");
    assert!(
        e.contains("`specularsplits` must be at most 64, found 65"),
        "{e}"
    );
    let e = error("Integrator \"photon\" \"integer gatherrays\" [ -1 ]\nWorldBegin\n");
    assert!(e.starts_with("s.pbrt:3:"), "{e}");
    assert!(e.contains("`gatherrays` must be >= 0"), "{e}");
    assert!(load("Integrator \"photon\" \"integer specularsplits\" [ 64 ]\nWorldBegin\n").is_ok());
}

/// A photon float parameter's values `bad` are errors located at the
/// parameter that say `message`; `good` loads.
fn float_param_is_checked(name: &str, bad: &[&str], good: &str, message: &str) {
    let scene = |v: &str| format!("Integrator \"photon\" \"float {name}\" [ {v} ]\nWorldBegin\n");
    for v in bad {
        let e = error(&scene(v));
        assert!(e.starts_with("s.pbrt:3:"), "{e}");
        assert!(e.contains(message), "{e}");
    }
    assert!(load(&scene(good)).is_ok());
}

#[test]
fn a_gather_gain_that_is_not_positive_is_a_located_error() {
    let message = "`gathergain` must be a positive number";
    float_param_is_checked("gathergain", &["0", "-2"], "0.5", message);
}

#[test]
fn a_gather_boost_below_one_or_above_64_is_a_located_error() {
    let message = "`gatherboost` must be a number from 1 to 64";
    float_param_is_checked("gatherboost", &["0.5", "-1", "65"], "4", message);
}
