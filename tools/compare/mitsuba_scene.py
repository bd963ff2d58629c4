#!/usr/bin/env python3
"""Builds a Mitsuba 3 scene from mira's exported world and (optionally) renders it.

Input: a directory written by `export_obj` (tools/compare/export_obj): one world-space
OBJ per instance (`usemtl` per triangle) and `scene.json` (camera, lights, instances).

Output: `OUTDIR/mitsuba.xml` plus one OBJ per (instance, material) under `OUTDIR/meshes/`
(Mitsuba's OBJ loader ignores `usemtl`, so the meshes are split by material here).
With `--render FILE.exr` the scene is also rendered with the `scalar_rgb` variant.

What is matched to mira (see README.md):
  * materials: two-sided Lambertian (`twosided` + `diffuse`), albedo from --albedo
    (defaults: the seed Cornell box's flex_material base colours);
  * lights: rectangles only; a one-sided `area` emitter of radiance --radiance
    (default 42/pi = light_omni intensity 42 in lumen_m2, i.e. exitance / pi), facing the
    normal mira reports; the light's own surface reflects nothing (mira's lights are not
    geometry);
  * camera: pinhole at mira's camera, horizontal fov 2*atan(aperture / (2*focal)),
    fov_axis "x", one-pixel box reconstruction filter;
  * integrator: `path`, --max-depth (Mitsuba counts path vertices: depth 1 = emitters seen
    directly; mira's default of 16 segments with NEE at the last hit equals Mitsuba 17).
"""

import argparse
import json
import math
import os
import sys

DEFAULT_ALBEDO = {
    "white": (0.7, 0.7, 0.7),
    "green": (0.15, 0.7, 0.15),
    "red": (0.7, 0.15, 0.15),
    "(no material)": (0.5, 0.5, 0.5),  # mira's fallback grey
}


def read_obj(path):
    """Returns (positions, normals, faces) with faces as (material, [v...], [n...] or None)."""
    pos, nrm, faces = [], [], []
    mat = "(no material)"
    with open(path) as f:
        for line in f:
            t = line.split()
            if not t or t[0].startswith("#"):
                continue
            if t[0] == "v":
                pos.append(tuple(float(x) for x in t[1:4]))
            elif t[0] == "vn":
                nrm.append(tuple(float(x) for x in t[1:4]))
            elif t[0] == "usemtl":
                mat = line.strip()[len("usemtl "):]
            elif t[0] == "f":
                vs, ns = [], []
                for c in t[1:]:
                    parts = c.split("/")
                    vs.append(int(parts[0]) - 1)
                    if len(parts) >= 3 and parts[2]:
                        ns.append(int(parts[2]) - 1)
                faces.append((mat, vs, ns if len(ns) == len(vs) else None))
    return pos, nrm, faces


def write_split(pos, nrm, faces, material, path):
    """Writes the faces of one material, with only the vertices they use."""
    remap, out_v, out_n, out_f = {}, [], [], []
    has_n = all(n is not None for m, _, n in faces if m == material)
    for m, vs, ns in faces:
        if m != material:
            continue
        idx = []
        for k, v in enumerate(vs):
            key = (v, ns[k] if has_n else None)
            if key not in remap:
                remap[key] = len(out_v) + 1
                out_v.append(pos[v])
                if has_n:
                    out_n.append(nrm[ns[k]])
            idx.append(remap[key])
        out_f.append(idx)
    with open(path, "w") as f:
        for p in out_v:
            f.write("v %.9g %.9g %.9g\n" % p)
        for n in out_n:
            f.write("vn %.9g %.9g %.9g\n" % n)
        for idx in out_f:
            if has_n:
                f.write("f " + " ".join("%d//%d" % (i, i) for i in idx) + "\n")
            else:
                f.write("f " + " ".join(str(i) for i in idx) + "\n")
    return has_n, len(out_f)


def xml_safe_id(s):
    return "".join(c if c.isalnum() or c in "_-" else "_" for c in s)


def fmt(v):
    return ", ".join("%.9g" % x for x in v)


def sub(a, b):
    return [a[i] - b[i] for i in range(3)]


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def dot(a, b):
    return sum(a[i] * b[i] for i in range(3))


def build(args):
    with open(os.path.join(args.export_dir, "scene.json")) as f:
        desc = json.load(f)
    albedo = dict(DEFAULT_ALBEDO)
    for a in args.albedo:
        name, rgb = a.split("=", 1)
        albedo[name] = tuple(float(x) for x in rgb.split(","))

    os.makedirs(os.path.join(args.outdir, "meshes"), exist_ok=True)
    w, h = args.resolution

    # Camera. camera_to_world is column-major (glam); camera looks down -Z, +Y up, +X to
    # the image's right. Mitsuba's lookat puts cross(up, dir) at the image's LEFT, which for
    # a right-handed camera frame is exactly camera -X: the image is not mirrored.
    cam = desc["camera"]
    m = cam["camera_to_world"]
    col = lambda i: m[4 * i:4 * i + 3]
    origin = col(3)
    fwd = [-x for x in col(2)]
    up = col(1)
    right = col(0)
    if dot(cross(fwd, up), right) < 0:  # camera frame is left-handed (mirroring): warn
        print("warning: mirrored camera frame; Mitsuba's image will be mirrored", file=sys.stderr)
    target = [origin[i] + fwd[i] for i in range(3)]
    fov_x = math.degrees(2.0 * math.atan(cam["aperture"] / (2.0 * cam["focal"])))
    if abs(w / h - cam["aspect"]) > 1e-6:
        print("note: image aspect %g differs from the camera's %g; fov is horizontal"
              % (w / h, cam["aspect"]), file=sys.stderr)

    out = []
    out.append('<scene version="3.0.0">')
    out.append('  <integrator type="path">')
    out.append('    <integer name="max_depth" value="%d"/>' % args.max_depth)
    out.append('    <integer name="rr_depth" value="%d"/>' % args.rr_depth)
    out.append('    <boolean name="hide_emitters" value="false"/>')
    out.append('  </integrator>')
    out.append('  <sensor type="perspective">')
    out.append('    <string name="fov_axis" value="x"/>')
    out.append('    <float name="fov" value="%.9g"/>' % fov_x)
    out.append('    <float name="near_clip" value="0.001"/>')
    out.append('    <float name="far_clip" value="1e7"/>')
    out.append('    <transform name="to_world">')
    out.append('      <lookat origin="%s" target="%s" up="%s"/>' % (fmt(origin), fmt(target), fmt(up)))
    out.append('    </transform>')
    out.append('    <sampler type="%s">' % args.sampler)
    out.append('      <integer name="sample_count" value="%d"/>' % args.spp)
    out.append('    </sampler>')
    out.append('    <film type="hdrfilm">')
    out.append('      <integer name="width" value="%d"/>' % w)
    out.append('      <integer name="height" value="%d"/>' % h)
    out.append('      <string name="pixel_format" value="rgb"/>')
    out.append('      <rfilter type="box"/>')  # radius 0.5: one pixel
    out.append('    </film>')
    out.append('  </sensor>')

    used = set()
    for inst in desc["instances"]:
        pos, nrm, faces = read_obj(os.path.join(args.export_dir, inst["file"]))
        for mat in sorted(set(f[0] for f in faces)):
            used.add(mat)
            fname = "meshes/%s__%s.obj" % (xml_safe_id(inst["name"]), xml_safe_id(mat))
            has_n, n = write_split(pos, nrm, faces, mat, os.path.join(args.outdir, fname))
            out.append('  <shape type="obj" id="%s__%s">' % (xml_safe_id(inst["name"]), xml_safe_id(mat)))
            out.append('    <string name="filename" value="%s"/>' % fname)
            # Without normals in the file, shade with the geometric normal (as mira does).
            out.append('    <boolean name="face_normals" value="%s"/>' % ("false" if has_n else "true"))
            out.append('    <ref id="mat_%s"/>' % xml_safe_id(mat))
            out.append('  </shape>')
    bsdfs = []
    for mat in sorted(used):
        if mat not in albedo:
            sys.exit("no albedo for material '%s': pass --albedo '%s=r,g,b'" % (mat, mat))
        bsdfs.append('  <bsdf type="twosided" id="mat_%s">' % xml_safe_id(mat))
        bsdfs.append('    <bsdf type="diffuse"><rgb name="reflectance" value="%s"/></bsdf>' % fmt(albedo[mat]))
        bsdfs.append('  </bsdf>')
    out[1:1] = bsdfs

    radiance = args.radiance if args.radiance is not None else 42.0 / math.pi
    for li in desc["lights"]:
        if li.get("shape") != "rectangle":
            sys.exit("light '%s': only rectangle lights are supported here" % li["name"])
        u, v, n, c = li["edge_u"], li["edge_v"], li["normal"], li["position"]
        hu = [x / 2 for x in u]
        hv = [x / 2 for x in v]
        # Mitsuba's rectangle is [-1,1]^2 in local XY, facing local +Z. Keep the matrix
        # non-mirroring with Z along the emitting normal: if u x v points away from the
        # normal, use -v (the same parallelogram).
        if dot(cross(u, v), n) < 0:
            hv = [-x for x in hv]
        rows = [[hu[i], hv[i], n[i], c[i]] for i in range(3)] + [[0, 0, 0, 1]]
        mat = " ".join("%.9g" % x for r in rows for x in r)
        out.append('  <shape type="rectangle" id="light_%s">' % xml_safe_id(li["name"]))
        out.append('    <transform name="to_world"><matrix value="%s"/></transform>' % mat)
        # mira's lights are not geometry: the emitter surface itself reflects nothing.
        out.append('    <bsdf type="diffuse"><rgb name="reflectance" value="0, 0, 0"/></bsdf>')
        out.append('    <emitter type="area"><rgb name="radiance" value="%s"/></emitter>'
                   % fmt([radiance] * 3))
        out.append('  </shape>')
        if not li.get("visible", True):
            print("note: light '%s' is invisible in mira; Mitsuba shows it" % li["name"], file=sys.stderr)
    out.append('</scene>')
    xml = os.path.join(args.outdir, "mitsuba.xml")
    with open(xml, "w") as f:
        f.write("\n".join(out) + "\n")
    print("wrote", xml, file=sys.stderr)
    return xml


def render(xml, args):
    import time
    import mitsuba as mi
    mi.set_variant(args.variant)
    scene = mi.load_file(xml)
    t0 = time.time()
    img = mi.render(scene, seed=args.seed, spp=args.spp)
    dt = time.time() - t0
    mi.Bitmap(img).write(args.render)
    print("rendered %s: %dx%d, %d spp, seed %d, max_depth %d, %.1f s (mitsuba %s, %s)"
          % (args.render, args.resolution[0], args.resolution[1], args.spp, args.seed,
             args.max_depth, dt, mi.__version__, args.variant), file=sys.stderr)


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("export_dir", help="directory written by export_obj")
    p.add_argument("outdir", help="where mitsuba.xml and meshes/ go")
    p.add_argument("--resolution", nargs=2, type=int, default=[256, 256], metavar=("W", "H"))
    p.add_argument("--spp", type=int, default=1024)
    p.add_argument("--max-depth", type=int, default=64)
    p.add_argument("--rr-depth", type=int, default=5)
    p.add_argument("--sampler", default="independent")
    p.add_argument("--albedo", action="append", default=[], metavar="NAME=R,G,B")
    p.add_argument("--radiance", type=float, default=None, help="light radiance (default 42/pi)")
    p.add_argument("--render", metavar="FILE.exr", help="also render the scene to this file")
    p.add_argument("--seed", type=int, default=0)
    p.add_argument("--variant", default="scalar_rgb")
    args = p.parse_args()
    xml = build(args)
    if args.render:
        render(xml, args)


if __name__ == "__main__":
    main()
