//! pbrt-v3 syntax read through pbrt-v4's `--upgrade` rules.

use lumis_scene::*;
use std::path::Path;

fn load(text: &str) -> SceneDesc {
    load_str(text, "v3.pbrt", Path::new(".")).unwrap_or_else(|e| panic!("{e}"))
}

fn names(ps: &ParamSet) -> Vec<String> {
    let mut v: Vec<String> = ps
        .params
        .iter()
        .map(|p| format!("{} {}", p.ty, p.name))
        .collect();
    v.sort();
    v
}

fn mat(text: &str) -> (Entity, Vec<String>) {
    let d = load(&format!("WorldBegin\n{text}"));
    let w = d.warnings.iter().map(|w| w.message.clone()).collect();
    (d.materials[0].entity.clone(), w)
}

#[test]
fn v3_materials_become_v4_materials() {
    let (e, w) = mat(r#"Material "glass" "float index" 1.25 "rgb Kr" [1 1 1]"#);
    assert_eq!(e.ty, "dielectric");
    assert_eq!(names(&e.params), ["float eta"]);
    assert_eq!(e.params.get_float("eta", 0.0).unwrap(), 1.25);
    assert!(w.is_empty());

    // The caustic-glass floor: Ks is not zero, so coated diffuse; Ks is lost (warned).
    let (e, w) = mat(
        r#"Material "uber" "float roughness" 0.01 "float index" 1 "color Kd" [0.64 0.64 0.64]
           "rgb Ks" [0.1 0.1 0.1] "rgb Kt" [0 0 0] "rgb opacity" [1 1 1]"#,
    );
    assert_eq!(e.ty, "coateddiffuse");
    assert_eq!(
        names(&e.params),
        ["float eta", "float roughness", "rgb reflectance"]
    );
    assert_eq!(w.len(), 1);
    assert!(w[0].contains("`Ks`"), "{w:?}");

    let (e, _) =
        mat(r#"Material "uber" "rgb Ks" [0 0 0] "float roughness" 0.1 "rgb Kd" [.5 .5 .5]"#);
    assert_eq!(e.ty, "diffuse");
    assert_eq!(names(&e.params), ["rgb reflectance"]);

    let (e, _) =
        mat(r#"Material "plastic" "rgb Kd" [.5 .5 .5] "rgb Ks" [.2 .2 .2] "float roughness" .1"#);
    assert_eq!(e.ty, "coateddiffuse");
    let (e, _) =
        mat(r#"Material "plastic" "rgb Kd" [.5 .5 .5] "rgb Ks" [0 0 0] "float roughness" .1"#);
    assert_eq!(
        (e.ty.as_str(), names(&e.params)),
        ("diffuse", vec!["rgb reflectance".to_string()])
    );

    let (e, w) =
        mat(r#"Material "substrate" "rgb Kd" [.5 .5 .5] "rgb Ks" [1 1 1] "float uroughness" .1"#);
    assert_eq!(e.ty, "coateddiffuse");
    assert_eq!(names(&e.params), ["float uroughness", "rgb reflectance"]);
    assert!(w.is_empty());

    let (e, w) =
        mat(r#"Material "matte" "rgb Kd" [.5 .5 .5] "float sigma" 20 "texture bumpmap" "b""#);
    assert_eq!(e.ty, "diffuse");
    assert_eq!(
        names(&e.params),
        ["rgb reflectance", "texture displacement"]
    );
    assert!(w.iter().any(|m| m.contains("sigma")), "{w:?}");

    let (e, _) = mat(
        r#"Material "metal" "spectrum eta" "metal-Au-eta" "spectrum k" "metal-Au-k" "float roughness" 0.1"#,
    );
    assert_eq!(e.ty, "conductor");
    assert_eq!(
        names(&e.params),
        ["float roughness", "spectrum eta", "spectrum k"]
    );

    // pbrt-v4 turns a mirror into smooth silver.
    let (e, w) = mat(r#"Material "mirror" "rgb Kr" [0.9 0.9 0.9]"#);
    assert_eq!(e.ty, "conductor");
    assert_eq!(
        names(&e.params),
        ["float roughness", "spectrum eta", "spectrum k"]
    );
    assert_eq!(
        e.params.get_spectrum("eta").unwrap(),
        Some(SpectrumValue::Named("metal-Ag-eta".into()))
    );
    assert_eq!(w.len(), 1, "Kr is dropped with a warning, as pbrt-v4 does");

    let (e, _) = mat(
        r#"Material "translucent" "rgb Kd" [.5 .5 .5] "rgb reflect" [0 0 0] "rgb transmit" [1 1 1] "float roughness" .1"#,
    );
    assert_eq!(e.ty, "diffusetransmission");
    assert_eq!(names(&e.params), ["rgb transmittance"]);

    let d = load(
        r#"WorldBegin MakeNamedMaterial "a" "string type" "matte"
           MakeNamedMaterial "b" "string type" "glass"
           MakeNamedMaterial "m" "string type" "mix" "string namedmaterial1" "a" "string namedmaterial2" "b" "rgb amount" [.25 .25 .25]"#,
    );
    let m = &d.materials[2].entity;
    assert_eq!(
        (
            d.materials[0].entity.ty.as_str(),
            d.materials[1].entity.ty.as_str()
        ),
        ("diffuse", "dielectric")
    );
    assert_eq!(m.ty, "mix");
    assert_eq!(m.params.get_float("amount", 0.0).unwrap(), 0.25);
    assert_eq!(
        m.params.param("materials").unwrap().value,
        Value::Strings(vec!["b".into(), "a".into()]),
        "pbrt-v4 swaps the order"
    );

    let e = load_str(
        "WorldBegin Material \"glass\" \"float index\" 1.5 \"float eta\" 1.5",
        "v3.pbrt",
        Path::new("."),
    )
    .unwrap_err();
    assert!(e.message.contains("both \"index\" and \"eta\""));
    let e = load_str(
        "WorldBegin Material \"uber\" \"rgb opacity\" [.5 .5 .5]",
        "v3.pbrt",
        Path::new("."),
    )
    .unwrap_err();
    assert!(e.message.contains("opacity"), "{e}");
}

#[test]
fn v4_materials_pass_unchanged() {
    let (e, w) =
        mat(r#"Material "coateddiffuse" "rgb reflectance" [.5 .5 .5] "float roughness" 0.1"#);
    assert_eq!(e.ty, "coateddiffuse");
    assert_eq!(names(&e.params), ["float roughness", "rgb reflectance"]);
    assert!(w.is_empty());
}

#[test]
fn v3_lights_film_and_options() {
    let d = load(
        r#"Film "image" "integer xresolution" 70 "float scale" 1.5 "float maxsampleluminance" 10
        PixelFilter "gaussian" "float xwidth" 2 "float alpha" 2
        Sampler "lowdiscrepancy" "integer pixelsamples" 4
        Integrator "directlighting"
        Camera "perspective"
        WorldBegin
        LightSource "spot" "point from" [0 5 9] "point to" [-5 2.75 0] "blackbody I" [5500 125]
        LightSource "infinite" "color L" [.1 .1 .1] "integer samples" 4
        LightSource "infinite" "string mapname" "sky.exr" "rgb L" [2 2 2] "float scale" 3
        LightSource "point" "rgb scale" [2 2 2] "blackbody I" [3000 0.5]
        AreaLightSource "area" "blackbody L" [6500 10] "integer nsamples" 4
        Shape "sphere"
        WorldEnd"#,
    );
    assert!(d.warnings.is_empty(), "{:?}", d.warnings);
    let film = d.film.as_ref().unwrap();
    assert_eq!(film.ty, "rgb");
    assert_eq!(film.params.get_float("iso", 0.0).unwrap(), 150.0);
    assert_eq!(
        film.params.get_float("maxcomponentvalue", 0.0).unwrap(),
        10.0
    );
    let f = d.filter.as_ref().unwrap();
    assert_eq!(f.params.get_float("xradius", 0.0).unwrap(), 2.0);
    assert!((f.params.get_float("sigma", 0.0).unwrap() - 0.5).abs() < 1e-6);
    assert_eq!(d.sampler.as_ref().unwrap().ty, "paddedsobol");
    let i = d.integrator.as_ref().unwrap();
    assert_eq!(
        (i.ty.as_str(), i.params.get_int("maxdepth", 0).unwrap()),
        ("path", 1)
    );

    let l = |k: usize| &d.lights[k].entity.params;
    assert_eq!(
        l(0).get_spectrum("I").unwrap(),
        Some(SpectrumValue::Blackbody(5500.0))
    );
    assert_eq!(l(0).get_float("scale", 1.0).unwrap(), 125.0);
    assert_eq!(names(l(1)), ["rgb L"]);
    assert_eq!(
        names(l(2)),
        ["float scale", "string filename", "string mapping"]
    );
    assert_eq!(l(2).get_float("scale", 1.0).unwrap(), 6.0);
    assert_eq!(l(3).get_float("scale", 1.0).unwrap(), 1.0);
    assert_eq!(
        names(l(3)),
        ["blackbody I"],
        "2 × 0.5: no scale left, as pbrt-v4"
    );
    let al = d.shapes[0].area_light.as_ref().unwrap();
    assert_eq!(al.ty, "diffuse");
    assert_eq!(names(&al.params), ["blackbody L", "float scale"]);
    assert_eq!(al.params.get_float("scale", 1.0).unwrap(), 10.0);
}

#[test]
fn v3_shapes_and_textures() {
    let d = load(
        r#"WorldBegin
        Texture "c" "color" "imagemap" "string filename" "a.png" "bool trilinear" true "bool gamma" false
        Texture "s" "color" "scale" "texture tex1" "c" "rgb tex2" [.5 .5 .5]
        Texture "f" "float" "scale" "texture tex1" "x" "float tex2" 2
        Shape "trianglemesh" "point P" [0 0 0 1 0 0 0 1 0] "integer indices" [0 1 2]
           "float uv" [0 0 1 0 0 1] "normal N" [0 0 1 0 0 1 0 0 1] "bool discarddegenerateUVs" true
        Shape "loopsubdiv" "integer nlevels" 3 "point P" [0 0 0 1 0 0 0 1 0] "integer indices" [0 1 2]"#,
    );
    assert!(d.warnings.is_empty(), "{:?}", d.warnings);
    let t = &d.textures[0];
    assert_eq!(t.kind, "spectrum");
    assert_eq!(
        names(&t.entity.params),
        ["string encoding", "string filename", "string filter"]
    );
    assert_eq!(
        t.entity.params.get_string("filter", "").unwrap(),
        "trilinear"
    );
    assert_eq!(
        t.entity.params.get_string("encoding", "").unwrap(),
        "linear"
    );
    assert_eq!(
        names(&d.textures[1].entity.params),
        ["float scale", "texture tex"]
    );
    assert_eq!(
        names(&d.textures[2].entity.params),
        ["float scale", "texture tex"]
    );
    let m = &d.shapes[0].entity.params;
    assert_eq!(m.get_point2s("uv").unwrap().unwrap().len(), 3);
    assert!(!m.has("discarddegenerateUVs"));
    assert_eq!(m.get_normals("N").unwrap().unwrap().len(), 3);
    assert_eq!(d.shapes[1].entity.params.get_int("levels", 0).unwrap(), 3);
}
