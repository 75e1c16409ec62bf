"""A reader for the small subset of pbrt-v4 the benchmark scenes use.

parse(path) returns a list of Statement (directive, positional args, params,
file:line); anything outside the subset is a located PbrtError, so a scene
that grows a feature the Mitsuba conversion does not know fails loudly
instead of being converted wrongly. write(statements) prints them back as
pbrt-v4 text.
"""

import re

TOKEN = re.compile(r'"[^"]*"|\[|\]|#[^\n]*|[^\s\[\]"#]+')
PARAM = re.compile(r"^(integer|float|point3|normal|rgb|spectrum|string|bool) (\w+)$")
DIRECTIVES = {
    "Integrator", "LookAt", "Sampler", "PixelFilter", "Film", "Camera", "WorldBegin",
    "MakeNamedMaterial", "NamedMaterial", "Material", "Shape", "AttributeBegin",
    "AttributeEnd", "Translate", "Scale", "AreaLightSource", "MakeNamedMedium",
    "MediumInterface",
}  # fmt: skip


class PbrtError(Exception):
    pass


class Statement:
    def __init__(self, name, args, params, loc):
        self.name, self.args, self.params, self.loc = name, args, params, loc

    def param(self, name, default=None):
        """The values of parameter `name` (a list), or default."""
        for (_, n), v in self.params.items():
            if n == name:
                return v
        return default

    def one(self, name, default=None):
        v = self.param(name)
        return default if v is None else v[0]

    def set(self, ty, name, values):
        self.params = {k: v for k, v in self.params.items() if k[1] != name}
        self.params[(ty, name)] = values


def _value(tok):
    if tok.startswith('"'):
        return tok[1:-1]
    if tok in ("true", "false"):
        return tok == "true"
    try:
        return float(tok)
    except ValueError:
        return None


def _is_word(tok):
    """A bare word: a directive (the parameters are quoted strings or numbers)."""
    return tok[0].isalpha() and tok not in ("true", "false")


def _tokens(text, path):
    line = 1
    pos = 0
    for m in TOKEN.finditer(text):
        line += text.count("\n", pos, m.start())
        pos = m.start()
        if not m.group().startswith("#"):
            yield m.group(), f"{path}:{line}"


def parse(path):
    with open(path) as f:
        toks = list(_tokens(f.read(), path))
    out, i = [], 0
    while i < len(toks):
        name, loc = toks[i]
        if name not in DIRECTIVES:
            raise PbrtError(f"{loc}: `{name}` is not in the subset the benchmark converts")
        i += 1
        args, params = [], {}
        while i < len(toks) and not _is_word(toks[i][0]):
            tok, tloc = toks[i]
            m = PARAM.match(tok[1:-1]) if tok.startswith('"') else None
            if m is None:
                if params or _value(tok) is None:
                    raise PbrtError(f"{tloc}: unexpected `{tok}` after {name}")
                args.append(_value(tok))
                i += 1
                continue
            i += 1
            if i < len(toks) and toks[i][0] == "[":
                j = i + 1
                while j < len(toks) and toks[j][0] != "]":
                    j += 1
                vals = [_value(t) for t, _ in toks[i + 1 : j]]
                i = j + 1
            else:
                vals = [_value(toks[i][0])]
                i += 1
            if any(v is None for v in vals):
                raise PbrtError(f"{tloc}: bad value of {tok}")
            params[(m.group(1), m.group(2))] = vals
        out.append(Statement(name, args, params, loc))
    return out


def _fmt(v):
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, str):
        return f'"{v}"'
    return f"{v:.9g}"


def write(statements):
    lines = []
    for s in statements:
        parts = [s.name] + [_fmt(a) for a in s.args]
        for (ty, name), vals in s.params.items():
            parts.append(f'"{ty} {name}" [ {" ".join(_fmt(v) for v in vals)} ]')
        lines.append(" ".join(parts))
    return "\n".join(lines) + "\n"
