use super::*;
use crate::lexer::tokenize;
use crate::loc::SourceFile;

fn ps(text: &str) -> Result<ParamSet, Diagnostic> {
    ParamSet::parse(&tokenize(&SourceFile::new("p.pbrt", text)).unwrap())
}

#[test]
fn every_value_type() {
    let p = ps(
        r#""integer n" [ 1 2 ] "float f" 2.5 "point2 uv" [0 0 1 1] "vector2 d" [1 2]
        "point3 P" [1 2 3] "point Q" [4 5 6] "vector3 v" [0 0 1] "vector w" [1 0 0]
        "normal3 N" [0 1 0] "normal M" [0 0 1] "rgb c" [1 0.5 0] "color k" [0 0 1]
        "bool b" true "bool b2" "false" "string s" "hi" "texture t" "tex"
        "spectrum sp" [300 1 800 2] "spectrum eta" "metal-Cu-eta" "spectrum kk" "spds/Au.k.spd"
        "blackbody I" 5500"#,
    )
    .unwrap();
    assert_eq!(p.get_ints("n").unwrap(), Some(vec![1, 2]));
    assert_eq!(p.get_float("f", 0.0).unwrap(), 2.5);
    assert_eq!(
        p.get_point2s("uv").unwrap().unwrap()[1],
        Vec2::new(1.0, 1.0)
    );
    assert_eq!(p.param("d").unwrap().ty, "vector2");
    assert_eq!(
        p.get_point3s("P").unwrap(),
        Some(vec![Vec3::new(1.0, 2.0, 3.0)])
    );
    assert_eq!(p.param("Q").unwrap().ty, "point3");
    assert_eq!(
        p.get_point3("Q", Vec3::ZERO).unwrap(),
        Vec3::new(4.0, 5.0, 6.0)
    );
    assert_eq!(p.get_vector3("v", Vec3::ZERO).unwrap(), Vec3::Z);
    assert_eq!(p.get_vector3("w", Vec3::ZERO).unwrap(), Vec3::X);
    assert_eq!(p.get_normals("N").unwrap(), Some(vec![Vec3::Y]));
    assert_eq!(p.param("M").unwrap().ty, "normal");
    assert_eq!(
        p.get_spectrum("c").unwrap(),
        Some(SpectrumValue::Rgb([1.0, 0.5, 0.0]))
    );
    assert_eq!(p.param("k").unwrap().ty, "rgb");
    assert_eq!(p.param("kk").unwrap().ty, "spectrum");
    assert_eq!(p.param("c").unwrap().ty, "rgb");
    assert!(!p.get_bool("b2", true).unwrap());
    assert!(p.get_bool("b", false).unwrap());
    assert_eq!(p.get_string("s", "").unwrap(), "hi");
    assert_eq!(p.get_texture("t").as_deref(), Some("tex"));
    assert_eq!(
        p.get_spectrum("sp").unwrap(),
        Some(SpectrumValue::Sampled(vec![(300.0, 1.0), (800.0, 2.0)]))
    );
    assert_eq!(
        p.get_spectrum("eta").unwrap(),
        Some(SpectrumValue::Named("metal-Cu-eta".into()))
    );
    assert_eq!(
        p.get_spectrum("kk").unwrap(),
        Some(SpectrumValue::File("spds/Au.k.spd".into()))
    );
    assert_eq!(
        p.get_spectrum("I").unwrap(),
        Some(SpectrumValue::Blackbody(5500.0))
    );
    let unused: Vec<_> = p.unused().iter().map(|p| p.name.clone()).collect();
    assert_eq!(unused, vec!["d", "M", "k"]);
}

#[test]
fn defaults_and_value_locations() {
    let p = ps("\"float fov\" [ 45 ]").unwrap();
    assert_eq!(p.get_float("missing", 3.0).unwrap(), 3.0);
    assert_eq!(p.get_opt_string("missing").unwrap(), None);
    assert_eq!(p.get_spectrum("missing").unwrap(), None);
    let fov = p.param("fov").unwrap();
    assert_eq!((fov.loc.col, fov.loc.len), (1, 11));
    assert_eq!(fov.value_locs[0].col, 15);
    assert!(p.has("fov") && p.loc_of("fov").is_some());
}

#[test]
fn integer_accepted_as_float_but_not_float_as_integer() {
    let p = ps("\"integer n\" 3").unwrap();
    assert_eq!(p.get_float("n", 0.0).unwrap(), 3.0);
    let e = ps("\"integer n\" 3.5").unwrap_err();
    assert!(e.message.contains("expected an integer"), "{e}");
    assert_eq!(e.loc.unwrap().col, 13);
}

#[test]
fn wrong_type_is_an_error_at_the_parameter() {
    let p = ps("Shape \"string fov\" \"wide\"".trim_start_matches("Shape ")).unwrap();
    let e = p.get_float("fov", 1.0).unwrap_err();
    assert!(
        e.message.contains("should have type `float` or `integer`"),
        "{e}"
    );
    assert!(e.message.contains("declared as `string`"), "{e}");
    assert_eq!(e.loc.unwrap().line, 1);
}

#[test]
fn wrong_arity_is_an_error() {
    let p =
        ps("\"rgb c\" [1 2] \"float f\" [1 2 3] \"point3 P\" [1 2 3 4] \"spectrum s\" [400 1 500]")
            .unwrap();
    assert!(p
        .get_spectrum("c")
        .unwrap_err()
        .message
        .contains("exactly 3 values"));
    assert!(p
        .get_float("f", 0.0)
        .unwrap_err()
        .message
        .contains("exactly 1 value"));
    assert!(p.get_point3s("P").is_err());
    assert!(p
        .get_spectrum("s")
        .unwrap_err()
        .message
        .contains("even number"));
}

#[test]
fn wrong_value_kinds_are_errors_with_caret() {
    let e = ps("\"float f\" \"x\"").unwrap_err();
    assert!(e.message.contains("expected a number"), "{e}");
    assert_eq!(e.loc.as_ref().unwrap().col, 11);
    assert!(e.to_string().contains("^^^"));
    assert!(ps("\"string s\" 1")
        .unwrap_err()
        .message
        .contains("quoted string"));
    assert!(ps("\"bool b\" \"yes\"")
        .unwrap_err()
        .message
        .contains("true or false"));
    assert!(ps("\"spectrum s\" [ \"a\" 1 ]").is_err());
}

#[test]
fn bad_declarations() {
    let e = ps("\"flaot radius\" 1").unwrap_err();
    assert!(e.message.contains("unknown parameter type `flaot`"));
    assert_eq!(e.help.as_deref(), Some("did you mean `float`?"));
    assert!(ps("\"radius\" 1")
        .unwrap_err()
        .message
        .contains("not a parameter declaration"));
    assert!(ps("\"float a b\" 1").is_err());
    assert!(ps("\"float r\"")
        .unwrap_err()
        .message
        .contains("has no value"));
    assert!(ps("\"float r\" [ 1")
        .unwrap_err()
        .message
        .contains("unclosed"));
    assert!(ps("1 2")
        .unwrap_err()
        .message
        .contains("expected a parameter declaration"));
}

#[test]
fn redefinition_is_an_error() {
    let e = ps("\"float r\" 1 \"float r\" 2").unwrap_err();
    assert!(e.message.contains("parameter `r` redefined"));
    assert_eq!(e.loc.unwrap().col, 13);
}

#[test]
fn report_unused_suggests_near_names() {
    let p = ps("\"rgb reflectence\" [1 1 1] \"float sigma\" 0 \"float zzz\" 1 \"float used\" 1")
        .unwrap();
    p.get_float("used", 0.0).unwrap();
    let w = p.report_unused("material `diffuse`", &["reflectance", "sigma", "used"]);
    assert_eq!(w.len(), 2, "{w:?}");
    assert_eq!(
        w[0].message,
        "unknown parameter `reflectence` for material `diffuse`"
    );
    assert_eq!(w[0].help.as_deref(), Some("did you mean `reflectance`?"));
    assert_eq!(w[0].severity, crate::loc::Severity::Warning);
    assert!(w[1].help.is_none());
    p.mark_used("zzz");
    assert_eq!(p.unused().len(), 2);
}

#[test]
fn texture_lookup_leaves_other_types_alone() {
    let p = ps("\"rgb reflectance\" [1 1 1]").unwrap();
    assert_eq!(p.get_texture("reflectance"), None);
    assert!(!p.param("reflectance").unwrap().is_used());
    let e = ps("\"blackbody L\" [6500 1]")
        .unwrap()
        .get_spectrum("L")
        .unwrap_err();
    assert!(e.help.unwrap().contains("pbrt-v3"));
}
