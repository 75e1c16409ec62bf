//! Every class of scene error: location, caret and message.

use lumis_scene::*;
use std::path::Path;

fn err(text: &str) -> Diagnostic {
    match load_str(text, "scene.pbrt", Path::new("/nowhere")) {
        Ok(_) => panic!("expected an error for {text:?}"),
        Err(e) => e,
    }
}

fn at(e: &Diagnostic) -> (u32, u32) {
    let l = e.loc.as_ref().expect("located");
    (l.line, l.col)
}

#[test]
fn syntax_error_has_file_line_col_and_caret() {
    let e = err("WorldBegin\nShape \"sphere\n");
    let s = e.to_string();
    assert!(
        s.contains("scene.pbrt:2:7: error: unterminated string"),
        "{s}"
    );
    assert!(s.contains("    2 | Shape \"sphere\n      |       ^"), "{s}");
    let e = err("WorldBegin\n  Shape \"sphere\" \"float radius\" 1 2");
    assert_eq!(at(&e), (2, 35));
    assert!(
        e.message.contains("expected a parameter declaration"),
        "{e}"
    );
    assert!(err("[ 1 ]").message.contains("expected a directive"));
}

#[test]
fn wrong_parameter_value_type() {
    let e = err("WorldBegin\nShape \"sphere\" \"float radius\" \"big\"");
    assert_eq!(at(&e), (2, 31));
    assert!(e.message.contains("expected a number"), "{e}");
    let e = err("WorldBegin\nShape \"sphere\" \"flaot radius\" 1");
    assert_eq!(e.help.as_deref(), Some("did you mean `float`?"));
}

#[test]
fn wrong_type_found_by_getter() {
    let d = load_str(
        "Camera \"perspective\" \"string fov\" \"45\"\nWorldBegin",
        "s.pbrt",
        Path::new("."),
    )
    .unwrap();
    let e = d
        .camera
        .unwrap()
        .entity
        .params
        .get_float("fov", 90.0)
        .unwrap_err();
    assert_eq!(at(&e), (1, 22));
    assert!(
        e.message.contains("`float`") && e.message.contains("`string`"),
        "{e}"
    );
}

#[test]
fn wrong_arity() {
    let e = err("Translate 1 2\nWorldBegin");
    assert!(e.message.contains("expects 3 numbers, found 2"), "{e}");
    assert_eq!(at(&e), (1, 1));
    let e = err("Transform [1 0 0 0 0 1 0 0 0 0 1 0 0 0 0]");
    assert!(e.message.contains("expects 16 numbers"), "{e}");
    let e = err("LookAt 0 0 0 0 0 1 0 0 \"x\"");
    assert_eq!(at(&e), (1, 24));
    let d = load_str(
        "WorldBegin LightSource \"point\" \"rgb I\" [1 2]",
        "s",
        Path::new("."),
    )
    .unwrap();
    let e = d.lights[0].entity.params.get_spectrum("I").unwrap_err();
    assert!(e.message.contains("exactly 3 values"), "{e}");
}

#[test]
fn unknown_directive_with_suggestion() {
    let e = err("WorldBegin\nShapee \"sphere\"");
    assert_eq!(e.message, "unknown directive `Shapee`");
    assert_eq!(e.help.as_deref(), Some("did you mean `Shape`?"));
    assert_eq!(at(&e), (2, 1));
    assert_eq!(e.loc.unwrap().len, 6);
    assert!(err("Frobnicate").help.is_none());
}

#[test]
fn unbalanced_attribute_end() {
    let e = err("WorldBegin\nAttributeBegin\nAttributeEnd\nAttributeEnd");
    assert_eq!(at(&e), (4, 1));
    assert!(e.message.contains("without a matching begin"), "{e}");
    let e = err("WorldBegin\nTransformBegin\nAttributeEnd");
    assert!(e.message.contains("does not match"), "{e}");
}

#[test]
fn missing_include_file() {
    let e = err("WorldBegin\nInclude \"geometry/nothing.pbrt\"");
    assert_eq!(at(&e), (2, 9));
    assert!(e.message.contains("/nowhere/geometry/nothing.pbrt"), "{e}");
    let e = load_file(Path::new("/nowhere/top.pbrt")).unwrap_err();
    assert!(e.loc.is_none() && e.message.contains("/nowhere/top.pbrt"));
}

#[test]
fn directives_in_the_wrong_block() {
    let e = err("Shape \"sphere\"\nWorldBegin");
    assert!(e.message.contains("only allowed after WorldBegin"), "{e}");
    assert_eq!(at(&e), (1, 1));
    let e = err("WorldBegin\nCamera \"perspective\"");
    assert!(e.message.contains("not allowed after WorldBegin"), "{e}");
    assert_eq!(at(&e), (2, 1));
    for d in [
        "LightSource \"point\"",
        "Material \"diffuse\"",
        "Texture \"t\" \"float\" \"constant\"",
        "ReverseOrientation",
    ] {
        assert!(
            err(d).message.contains("only allowed after WorldBegin"),
            "{d}"
        );
    }
    assert!(err("WorldBegin WorldBegin").message.contains("twice"));
}

#[test]
fn malformed_directive_arguments() {
    assert!(err("WorldBegin Shape")
        .message
        .contains("missing arguments"));
    assert!(err("WorldBegin Shape 1").message.contains("quoted string"));
    assert!(
        err("WorldBegin MakeNamedMaterial \"m\" \"rgb reflectance\" [1 1 1]")
            .message
            .contains("no \"string type\"")
    );
    assert!(err("WorldBegin Texture \"t\" \"vector\" \"constant\"")
        .message
        .contains("\"float\" or \"spectrum\""));
    assert!(err("WorldBegin 1").message.contains("takes no arguments"));
    assert!(err("Scale 0 1 1").message.contains("singular"));
    assert!(err("Rotate 30 0 0 0").message.contains("axis is zero"));
    assert!(err("LookAt 0 0 0  0 1 0  0 1 0")
        .message
        .contains("parallel"));
}

#[test]
fn unknown_parameter_warning_with_did_you_mean() {
    let d = load_str(
        "WorldBegin\nMaterial \"diffuse\" \"rgb reflectence\" [1 1 1]",
        "s.pbrt",
        Path::new("."),
    )
    .unwrap();
    let w = d.materials[0]
        .entity
        .params
        .report_unused("material `diffuse`", &["reflectance", "sigma"]);
    assert_eq!(w.len(), 1);
    let s = w[0].to_string();
    assert!(
        s.starts_with(
            "s.pbrt:2:20: warning: unknown parameter `reflectence` for material `diffuse`"
        ),
        "{s}"
    );
    assert!(s.ends_with("= help: did you mean `reflectance`?"), "{s}");
}
