#!/usr/bin/env python3
"""Writes one benchmark scene for pbrt-v4 / lumis and for Mitsuba 3.

  python3 scripts/bench/convert.py SCENE.pbrt OUT_DIR NAME --res WxH --maxdepth D

OUT_DIR/NAME.pbrt is SCENE.pbrt with Integrator "path" and maxdepth D, the
film at WxH, and a gaussian filter's radius written out as 4 sigma, the
radius Mitsuba's gaussian has (pbrt-v4's default is 1.5); mesh file names
become absolute. OUT_DIR/NAME.xml is the same scene for Mitsuba 3, with
inline triangle meshes written as OUT_DIR/NAME-mesh-K.ply. How each thing
is matched:
- camera: pbrt's LookAt is left-handed (camera +x is image right), Mitsuba's
  look_at puts camera +x on the image left: a scale(-1, 1, 1) before it
  mirrors it back; fov is over the shorter image axis in both;
- max depth: pbrt's maxdepth counts scattering events (0: emitters seen
  directly), Mitsuba's max_depth counts path segments (1: emitters seen
  directly), so max_depth = maxdepth + 1; Russian roulette from the second
  scattering on as in pbrt-v4 (rr_depth 2);
- materials: diffuse; dielectric with int_ior eta, ext_ior 1; conductor with
  pbrt's named metal spectra -> Mitsuba's material preset, or reflectance
  -> material "none" (a perfect mirror) times that reflectance; pbrt's
  roughness r -> GGX alpha sqrt(r) (pbrt-v4's remapping); opaque BSDFs are
  two-sided, as pbrt's are;
- area lights: diffuse, one-sided, rgb L -> area emitter radiance;
- media: homogeneous with rgb sigma_a, sigma_s, scale and g -> Mitsuba's
  homogeneous (sigma_t and albedo, hg phase); MediumInterface on a shape ->
  its interior and exterior (when they differ), at the Camera -> the
  sensor's medium; material "interface" -> bsdf "null"; the integrator is
  then volpath.
"""

import argparse
import math
import os
import sys

from pbrt_scene import PbrtError, parse, write

HERE = os.path.dirname(os.path.abspath(__file__))


def rgb(vals):
    return ",".join(f"{v:.9g}" for v in vals)


def metal(s, name):
    """pbrt's named spectrum `metal-Au-eta` -> Mitsuba's preset `Au`."""
    v = s.one(name)
    if not (isinstance(v, str) and v.startswith("metal-") and v.endswith("-" + name)):
        raise PbrtError(f"{s.loc}: conductor `{name}` must be a named metal spectrum")
    return v.split("-")[1]


def bsdf_xml(s, ty, ident=""):
    """Mitsuba BSDF for a pbrt material statement of type `ty`."""
    idattr = f' id="{ident}"' if ident else ""
    if ty == "interface":
        return '<bsdf type="null"/>'
    if ty == "diffuse":
        refl = s.param("reflectance", [0.5, 0.5, 0.5])
        inner = f'<bsdf type="diffuse"><rgb name="reflectance" value="{rgb(refl)}"/></bsdf>'
    elif ty == "dielectric":
        if s.one("roughness", 0) != 0:
            raise PbrtError(f"{s.loc}: rough dielectrics are not converted")
        eta = s.one("eta", 1.5)
        return (
            f'<bsdf type="dielectric"{idattr}><float name="int_ior" value="{eta}"/>'
            '<float name="ext_ior" value="1"/></bsdf>'
        )
    elif ty == "conductor":
        refl = s.param("reflectance")
        if refl is not None:
            props = '<string name="material" value="none"/>'
            props += f'<rgb name="specular_reflectance" value="{rgb(refl)}"/>'
        else:
            a, b = metal(s, "eta"), metal(s, "k")
            if a != b:
                raise PbrtError(f"{s.loc}: eta and k of different metals")
            props = f'<string name="material" value="{a}"/>'
        r = s.one("roughness", 0.0)
        if s.param("uroughness") or s.param("vroughness"):
            raise PbrtError(f"{s.loc}: anisotropic roughness is not converted")
        if r > 0:
            alpha = math.sqrt(r) if s.one("remaproughness", True) else r
            props += f'<string name="distribution" value="ggx"/><float name="alpha" value="{alpha:.9g}"/>'
            inner = f'<bsdf type="roughconductor">{props}</bsdf>'
        else:
            inner = f'<bsdf type="conductor">{props}</bsdf>'
    else:
        raise PbrtError(f"{s.loc}: material `{ty}` is not converted")
    return f'<bsdf type="twosided"{idattr}>{inner}</bsdf>'


def write_ply(path, pts, idx):
    with open(path, "w") as f:
        f.write(f"ply\nformat ascii 1.0\nelement vertex {len(pts) // 3}\n")
        f.write("property float x\nproperty float y\nproperty float z\n")
        f.write(f"element face {len(idx) // 3}\nproperty list uchar int vertex_indices\nend_header\n")
        for k in range(0, len(pts), 3):
            f.write(" ".join(f"{v:.9g}" for v in pts[k : k + 3]) + "\n")
        for k in range(0, len(idx), 3):
            f.write("3 " + " ".join(str(int(v)) for v in idx[k : k + 3]) + "\n")


class Converter:
    def __init__(self, src, out_dir, name, res, maxdepth):
        self.src_dir = os.path.dirname(os.path.abspath(src))
        self.out_dir, self.name, self.res, self.maxdepth = out_dir, name, res, maxdepth
        self.xml, self.meshes = [], 0
        # graphics state: translation, uniform scale, material (xml or ref), area light
        self.state = {"t": [0.0, 0.0, 0.0], "s": 1.0, "mat": None, "light": None, "media": ("", "")}
        self.stack = []
        self.media = []

    def run(self, stmts):
        head = {}
        for s in stmts:
            getattr(self, "do_" + s.name, self.do_other)(s, head)
        cam = head["Camera"]
        eye, look, up = (cam.args[0:3], cam.args[3:6], cam.args[6:9])
        w, h = self.res
        filt = head.get("PixelFilter")
        rfilter = '<rfilter type="box"/>'
        if filt is not None and filt.args[0] == "gaussian":
            rfilter = (
                f'<rfilter type="gaussian"><float name="stddev" value="{filt.one("sigma", 0.5)}"/></rfilter>'
            )
        integrator = "volpath" if self.media else "path"
        cam_medium = f'<ref name="medium" id="{head["medium"]}"/>' if head.get("medium") else ""
        scene = [
            '<scene version="3.0.0">',
            f'<integrator type="{integrator}"><integer name="max_depth" value="{self.maxdepth + 1}"/>'
            '<integer name="rr_depth" value="2"/></integrator>',
            *self.media,
            f'<sensor type="perspective">{cam_medium}'
            f'<float name="fov" value="{head["fov"]}"/><string name="fov_axis" value="smaller"/>'
            f'<transform name="to_world"><scale x="-1"/><lookat origin="{rgb(eye)}" '
            f'target="{rgb(look)}" up="{rgb(up)}"/></transform>'
            '<sampler type="independent"><integer name="sample_count" value="16"/></sampler>'
            f'<film type="hdrfilm"><integer name="width" value="{w}"/>'
            f'<integer name="height" value="{h}"/><string name="pixel_format" value="rgb"/>'
            '<boolean name="sample_border" value="true"/>'
            f"{rfilter}</film></sensor>",
        ]
        return "\n".join(scene + self.xml + ["</scene>"]) + "\n"

    # Options block: remembered for the sensor, rewritten for the bench pbrt file.
    def do_Integrator(self, s, head):
        s.args, s.params = ["path"], {}
        s.set("integer", "maxdepth", [self.maxdepth])

    def do_LookAt(self, s, head):
        head["Camera"] = s

    def do_Camera(self, s, head):
        if s.args != ["perspective"] or {n for _, n in s.params} - {"fov"}:
            raise PbrtError(f"{s.loc}: only a perspective camera with fov is converted")
        head["fov"] = s.one("fov", 90.0)
        head["medium"] = self.state["media"][1]

    def do_Film(self, s, head):
        s.set("integer", "xresolution", [self.res[0]])
        s.set("integer", "yresolution", [self.res[1]])
        s.set("string", "filename", [self.name + ".exr"])

    def do_PixelFilter(self, s, head):
        if s.args[0] not in ("gaussian", "box"):
            raise PbrtError(f"{s.loc}: filter `{s.args[0]}` is not converted")
        head["PixelFilter"] = s
        # lumis' own "bool splat": pbrt-v4 refuses it, and lumis splats a
        # filter wider than a pixel without it, as Mitsuba's film does.
        if s.param("splat") not in (None, [True]):
            raise PbrtError(f"{s.loc}: the copy splats, as Mitsuba does")
        s.params = {k: v for k, v in s.params.items() if k[1] != "splat"}
        if s.args[0] == "gaussian":
            r = 4 * s.one("sigma", 0.5)
            if s.one("xradius", r) != r or s.one("yradius", r) != r:
                raise PbrtError(f"{s.loc}: Mitsuba's gaussian radius is 4 sigma")
            s.set("float", "xradius", [r])
            s.set("float", "yradius", [r])
        elif s.param("xradius") or s.param("yradius"):
            raise PbrtError(f"{s.loc}: Mitsuba's box filter has radius 0.5")

    def do_other(self, s, head):  # Sampler, WorldBegin: kept as they are
        pass

    def do_MakeNamedMedium(self, s, head):
        if s.one("type") != "homogeneous" or {n for _, n in s.params} - {"type", "sigma_a", "sigma_s", "scale", "g"}:
            raise PbrtError(f"{s.loc}: only homogeneous media with sigma_a, sigma_s, scale, g are converted")
        k = s.one("scale", 1.0)
        sa = [k * v for v in s.param("sigma_a", [1, 1, 1])]
        ss = [k * v for v in s.param("sigma_s", [1, 1, 1])]
        st = [a + b for a, b in zip(sa, ss, strict=True)]
        albedo = [b / t if t > 0 else 0 for b, t in zip(ss, st, strict=True)]
        # Mitsuba's rgb values are reflectance-like (at most 1): the largest
        # sigma_t goes into the medium's scale.
        top = max(st) or 1.0
        self.media.append(
            f'<medium type="homogeneous" id="{s.args[0]}"><rgb name="sigma_t" value="{rgb([v / top for v in st])}"/>'
            f'<float name="scale" value="{top:.9g}"/><rgb name="albedo" value="{rgb(albedo)}"/>'
            f'<phase type="hg"><float name="g" value="{s.one("g", 0.0)}"/></phase></medium>'
        )

    def do_MediumInterface(self, s, head):
        self.state["media"] = (s.args[0], s.args[-1])

    # World block
    def do_MakeNamedMaterial(self, s, head):
        self.xml.append(bsdf_xml(s, s.one("type"), s.args[0]))

    def do_NamedMaterial(self, s, head):
        self.state["mat"] = f'<ref id="{s.args[0]}"/>'

    def do_Material(self, s, head):
        self.state["mat"] = bsdf_xml(s, s.args[0])

    def do_AttributeBegin(self, s, head):
        self.stack.append(dict(self.state, t=list(self.state["t"])))

    def do_AttributeEnd(self, s, head):
        self.state = self.stack.pop()

    def do_Translate(self, s, head):
        k = self.state["s"]
        self.state["t"] = [t + k * a for t, a in zip(self.state["t"], s.args, strict=True)]

    def do_Scale(self, s, head):
        if not (s.args[0] == s.args[1] == s.args[2] > 0):
            raise PbrtError(f"{s.loc}: only uniform positive scales are converted")
        self.state["s"] *= s.args[0]

    def do_AreaLightSource(self, s, head):
        if s.args[0] != "diffuse" or s.one("twosided", False) or s.param("scale") or not s.param("L"):
            raise PbrtError(f"{s.loc}: only a one-sided diffuse area light with rgb L is converted")
        self.state["light"] = (
            f'<emitter type="area"><rgb name="radiance" value="{rgb(s.param("L"))}"/></emitter>'
        )

    def do_Shape(self, s, head):
        st, ty = self.state, s.args[0]
        if st["mat"] is None:
            raise PbrtError(f"{s.loc}: shape without a material")
        if ty == "sphere":
            if {n for _, n in s.params} - {"radius"}:
                raise PbrtError(f"{s.loc}: only full spheres are converted")
            r = st["s"] * s.one("radius", 1.0)
            geo = f'<shape type="sphere"><point name="center" value="{rgb(st["t"])}"/>'
            geo += f'<float name="radius" value="{r:.9g}"/>'
        else:
            if st["t"] != [0, 0, 0] or st["s"] != 1:
                raise PbrtError(f"{s.loc}: transformed meshes are not converted")
            if ty == "plymesh":
                path = os.path.join(self.src_dir, s.one("filename"))
                s.set("string", "filename", [path])
            elif ty == "trianglemesh" and {n for _, n in s.params} == {"P", "indices"}:
                path = os.path.join(os.path.abspath(self.out_dir), f"{self.name}-mesh-{self.meshes}.ply")
                write_ply(path, s.param("P"), s.param("indices"))
                self.meshes += 1
            else:
                raise PbrtError(f"{s.loc}: shape `{ty}` (or its parameters) is not converted")
            geo = f'<shape type="ply"><string name="filename" value="{path}"/>'
        inside, outside = st["media"]
        media = ""
        if inside != outside:
            media += f'<ref name="interior" id="{inside}"/>' if inside else ""
            media += f'<ref name="exterior" id="{outside}"/>' if outside else ""
        self.xml.append(geo + st["mat"] + (st["light"] or "") + media + "</shape>")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("scene")
    ap.add_argument("out_dir")
    ap.add_argument("name")
    ap.add_argument("--res", required=True, help="WxH")
    ap.add_argument("--maxdepth", type=int, required=True)
    a = ap.parse_args()
    res = tuple(int(v) for v in a.res.split("x"))
    os.makedirs(a.out_dir, exist_ok=True)
    try:
        stmts = parse(a.scene)
        xml = Converter(a.scene, a.out_dir, a.name, res, a.maxdepth).run(stmts)
    except PbrtError as e:
        sys.exit(f"convert.py: {e}")
    header = f"# {a.name}: {os.path.abspath(a.scene)} as written by scripts/bench/convert.py\n"
    with open(os.path.join(a.out_dir, a.name + ".pbrt"), "w") as f:
        f.write(header + write(stmts))
    with open(os.path.join(a.out_dir, a.name + ".xml"), "w") as f:
        f.write(xml)


if __name__ == "__main__":
    main()
