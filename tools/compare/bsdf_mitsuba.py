#!/usr/bin/env python3
"""Compares mira's microfacet BSDFs (rough conductor, rough dielectric) with Mitsuba 3's
`roughconductor` and `roughdielectric` (GGX, visible-normal sampling), value by value.

For each configuration and each of a few viewing directions wo it compares, at a fixed set
of incident directions wi (half drawn from Mitsuba's own sampling, so that they lie in the
lobe, plus the mirror direction and directions spread over the sphere):

* f(wo, wi) without the cosine (Mitsuba's `eval` includes |cos θ| of its `wo`, mira's wi:
  it is divided out here);
* the sampling density per solid angle (`pdf`);
* the albedo, the mean sample weight f·|cos θi|/pdf over many samples of a 3-D
  low-discrepancy (R3) sequence, on both sides.

Mitsuba 3's microfacet model uses Smith's *separable* masking-shadowing G1(wo)·G1(wi); mira
uses the *height-correlated* form 1/(1 + Λ(wo) + Λ(wi)) (Heitz 2014). mira's dump tool
therefore also prints its values with G1·G1 in place of G2 (computed from mira's own Λ):
those are compared like for like ("aligned"), and the raw difference is shown as the model
difference it is. Mitsuba runs in radiance mode, where roughdielectric scales transmission
by 1/η² as mira does. Mitsuba's si.wi is mira's wo; Mitsuba's wo is mira's wi.

Usage (from the repository root):
    pip install mitsuba
    python3 tools/compare/bsdf_mitsuba.py [--samples N] [--dump-bin PATH] [--verbose]

Without --dump-bin it builds and runs `cargo run --release -p shade --example bsdf_dump`.
"""

import argparse
import math
import subprocess
import sys

import mitsuba as mi

mi.set_variant("scalar_rgb")

# Complex indices at the sRGB primaries: gold (the usual RGB reduction of its measured
# spectrum) and a neutral grey metal.
GOLD = ((0.143119, 0.374957, 1.44248), (3.98316, 2.38572, 1.60322))
GREY = ((2.0, 2.0, 2.0), (3.0, 3.0, 3.0))
ROUGHNESSES = [(0.1, 0.1), (0.3, 0.3), (0.6, 0.6), (0.1, 0.4)]
DIELECTRIC_ETA = 1.5


def sph(theta_deg, phi_deg):
    t, p = math.radians(theta_deg), math.radians(phi_deg)
    return (math.sin(t) * math.cos(p), math.sin(t) * math.sin(p), math.cos(t))


def r3(i):
    """The i-th point of the R3 Kronecker sequence in [0, 1)^3 (as mira's dump tool)."""
    phi = 1.2207440846057595
    return [math.fmod(0.5 + i / phi ** (j + 1), 1.0) for j in range(3)]


def r2(i):
    g = 1.324717957244746
    return (math.fmod(0.5 + i / g, 1.0), math.fmod(0.5 + i / (g * g), 1.0))


def sphere_points(n):
    pts = []
    for i in range(n):
        u, v = r2(i + 1)
        z = 1.0 - 2.0 * u
        r = math.sqrt(max(0.0, 1.0 - z * z))
        pts.append((r * math.cos(2 * math.pi * v), r * math.sin(2 * math.pi * v), z))
    return pts


def configurations():
    """(name, mitsuba dict, mira command line, viewing directions)."""
    out = []
    outside = [sph(5, 30), sph(40, 60), sph(70, 150), sph(85, 10)]
    for metal_name, (eta, k) in (("gold", GOLD), ("grey", GREY)):
        for ax, ay in ROUGHNESSES:
            d = {
                "type": "roughconductor",
                "distribution": "ggx",
                "alpha_u": ax,
                "alpha_v": ay,
                "eta": {"type": "rgb", "value": list(eta)},
                "k": {"type": "rgb", "value": list(k)},
            }
            cmd = "conductor %r %r %s %s" % (ax, ay, " ".join(map(repr, eta)), " ".join(map(repr, k)))
            name = "conductor %s α=%s" % (metal_name, ax if ax == ay else "%s×%s" % (ax, ay))
            out.append((name, d, cmd, outside))
    for ax, ay in ROUGHNESSES:
        d = {
            "type": "roughdielectric",
            "distribution": "ggx",
            "alpha_u": ax,
            "alpha_v": ay,
            "int_ior": DIELECTRIC_ETA,
            "ext_ior": 1.0,
        }
        cmd = "dielectric %r %r %r" % (ax, ay, DIELECTRIC_ETA)
        alpha = ax if ax == ay else "%s×%s" % (ax, ay)
        out.append(("dielectric α=%s, wo outside" % alpha, d, cmd, outside))
        inside = [(x, y, -z) for (x, y, z) in outside]
        out.append(("dielectric α=%s, wo inside" % alpha, d, cmd, inside))
    return out


def mitsuba_side(bsdf, wo, wis, samples):
    """Mitsuba's f (cosine divided out), pdf at each wi, and the albedo (mean, std error)."""
    ctx = mi.BSDFContext()
    si = mi.SurfaceInteraction3f()
    si.wi = mi.Vector3f(*wo)
    evals, pdfs = [], []
    for wi in wis:
        v = mi.Vector3f(*wi)
        c = abs(wi[2])
        f = bsdf.eval(ctx, si, v)
        evals.append([f[i] / c if c > 0 else 0.0 for i in range(3)])
        pdfs.append(bsdf.pdf(ctx, si, v))
    s1 = [0.0] * 3
    s2 = [0.0] * 3
    for i in range(samples):
        u = r3(i)
        _, w = bsdf.sample(ctx, si, u[2], mi.Point2f(u[0], u[1]))
        for c in range(3):
            s1[c] += w[c]
            s2[c] += w[c] * w[c]
    mean = [s / samples for s in s1]
    err = [math.sqrt(max(0.0, b / samples - m * m) / samples) for b, m in zip(s2, mean)]
    return evals, pdfs, mean, err


def lobe_directions(bsdf, wo, n):
    """n directions sampled by Mitsuba (a 2-D grid of sample points), plus the mirror
    direction and 48 directions spread over the sphere."""
    ctx = mi.BSDFContext()
    si = mi.SurfaceInteraction3f()
    si.wi = mi.Vector3f(*wo)
    out = []
    for i in range(n):
        u = r3(1000 + 7 * i)
        bs, w = bsdf.sample(ctx, si, u[2], mi.Point2f(u[0], u[1]))
        if bs.pdf > 0 and max(w[0], w[1], w[2]) > 0:
            out.append((bs.wo[0], bs.wo[1], bs.wo[2]))
    out.append((-wo[0], -wo[1], wo[2]))
    out.extend(sphere_points(48))
    return out


def run_mira(lines, dump_bin):
    cmd = [dump_bin] if dump_bin else ["cargo", "run", "-q", "--release", "-p", "shade", "--example", "bsdf_dump"]
    res = subprocess.run(cmd, input="\n".join(lines) + "\n", capture_output=True, text=True, check=False)
    if res.returncode != 0:
        sys.exit("bsdf_dump failed:\n" + res.stderr)
    return [ln.split() for ln in res.stdout.splitlines() if ln.strip()]


def rel(a, b):
    m = max(abs(a), abs(b))
    return abs(a - b) / m if m > 0 else 0.0


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--samples", type=int, default=1 << 18, help="albedo samples per direction (Mitsuba)")
    ap.add_argument("--mira-samples", type=int, default=1 << 22, help="albedo samples per direction (mira)")
    ap.add_argument("--lobe-directions", type=int, default=48, help="wi per wo drawn from Mitsuba's sampling")
    ap.add_argument("--dump-bin", help="prebuilt bsdf_dump binary (default: cargo run --release)")
    ap.add_argument("--verbose", action="store_true", help="per-direction albedo values")
    args = ap.parse_args()

    configs = configurations()
    lines, plan = [], []
    mitsuba = []
    for name, d, cmd, wos in configs:
        bsdf = mi.load_dict(d)
        lines.append(cmd)
        per_wo = []
        for wo in wos:
            wis = lobe_directions(bsdf, wo, args.lobe_directions)
            for wi in wis:
                lines.append("eval %r %r %r %r %r %r" % (wo + wi))
            lines.append("albedo %r %r %r %d" % (wo + (args.mira_samples,)))
            per_wo.append((wo, wis, mitsuba_side(bsdf, wo, wis, args.samples)))
        mitsuba.append(per_wo)
        plan.append(name)
        print("Mitsuba: %s done" % name, file=sys.stderr)

    out = run_mira(lines, args.dump_bin)
    pos = 0
    rows = []
    for (name, _, _, _), per_wo in zip(configs, mitsuba):
        worst = {"eval": 0.0, "eval_raw": 0.0, "pdf": 0.0, "alb": 0.0, "alb_raw": 0.0, "alb_err": 0.0}
        small = 0.0
        n_pairs = 0
        for wo, wis, (m_eval, m_pdf, m_alb, m_err) in per_wo:
            fmax = max(max(e) for e in m_eval)
            for wi, me, mp in zip(wis, m_eval, m_pdf):
                rec = out[pos]
                pos += 1
                assert rec[0] == "eval", rec
                v = [float(x) for x in rec[1:]]
                raw, sep, pdf = v[0:3], v[3:6], v[6]
                for c in range(3):
                    if max(abs(me[c]), abs(sep[c])) >= 1e-3 * fmax:
                        worst["eval"] = max(worst["eval"], rel(sep[c], me[c]))
                        worst["eval_raw"] = max(worst["eval_raw"], rel(raw[c], me[c]))
                    else:
                        small = max(small, abs(sep[c] - me[c]) / fmax)
                if max(pdf, mp) > 1e-3:
                    worst["pdf"] = max(worst["pdf"], rel(pdf, mp))
                n_pairs += 1
            rec = out[pos]
            pos += 1
            assert rec[0] == "albedo", rec
            v = [float(x) for x in rec[1:]]
            a_raw, a_sep = v[0:3], v[3:6]
            for c in range(3):
                worst["alb"] = max(worst["alb"], rel(a_sep[c], m_alb[c]))
                worst["alb_raw"] = max(worst["alb_raw"], rel(a_raw[c], m_alb[c]))
                worst["alb_err"] = max(worst["alb_err"], m_err[c] / max(m_alb[c], 1e-9))
            if args.verbose:
                print(
                    "  %-36s wo=(%.3f %.3f %.3f) albedo Mitsuba %s  mira aligned %s  mira %s"
                    % (
                        name,
                        *wo,
                        " ".join("%.5f" % x for x in m_alb),
                        " ".join("%.5f" % x for x in a_sep),
                        " ".join("%.5f" % x for x in a_raw),
                    )
                )
        rows.append((name, n_pairs, worst, small))

    print()
    print("| configuration | pairs | f (aligned masking) | pdf | albedo (aligned) | albedo σ (Mitsuba) | f, mira's own G2 | albedo, mira's own G2 |")
    print("|---|---|---|---|---|---|---|---|")
    for name, n, w, small in rows:
        print(
            "| %s | %d | %.2e | %.2e | %.2e | %.1e | %.2e | %.2e |"
            % (name, n, w["eval"], w["pdf"], w["alb"], w["alb_err"], w["eval_raw"], w["alb_raw"])
        )
    print()
    print("Maximum relative differences, mira vs Mitsuba 3 (f and pdf over pairs where the value is at least")
    print("1e-3 of the direction's largest; below it the largest absolute difference over that maximum was")
    print("%.1e)." % max(r[3] for r in rows))
    bad = [r[0] for r in rows if r[2]["eval"] > 0.01 or r[2]["pdf"] > 0.01 or r[2]["alb"] > 0.01]
    if bad:
        print("DISAGREE (> 1%%): %s" % ", ".join(bad))
        return 1
    print("All aligned differences within 1%.")
    return 0


if __name__ == "__main__":
    sys.exit(main())
