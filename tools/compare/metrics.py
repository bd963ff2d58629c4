#!/usr/bin/env python3
"""Image-error metrics between mira and a reference renderer (Mitsuba 3).

    metrics.py --mira A.exr [B.exr] --ref R1.exr [R2.exr] [--outdir DIR] [--exposure E]

A, B: two mira renders with different seeds; R1, R2: two reference renders with
different seeds, all at the same resolution (and, for the noise comparison to mean
anything, the same sample count). With two of each, the equal-sample-count noise of each
renderer is measured (mira-vs-mira, ref-vs-ref) and compared with the mira-vs-ref error.

Metrics (b = the reference image, a = the image compared with it):
  relMSE = mean((a - b)^2 / (b^2 + 0.01))
  MARE   = mean(|a - b| / (|b| + 0.01))
  FLIP   (HDR-FLIP on the linear images, and LDR-FLIP on the tone-mapped ones) when
         `flip-evaluator` is installed; SSIM on tone-mapped luminance when scikit-image is.
Per channel, a least-squares scale s (ref ~= s * mira) is fitted; metrics are given both
raw and after applying s (the brief: "after fitting ONE scale factor per channel").

Noise model: for two independent unbiased renders X, Y of one image, E[relMSE(X, Y)] is
about var_X + var_Y (relative), so the mira-vs-ref error expected from noise alone is the
mean of relMSE(mira, mira) and relMSE(ref, ref).

Writes (with --outdir): side_by_side.png (mira | reference | false-colour difference),
diff.png (signed luminance difference, blue = mira darker, red = mira brighter, scaled to
+-4 sigma of the noise when two seeds of each are given), regions.png (the region boxes).
"""

import argparse
import json
import os
import sys

import numpy as np


def load_exr(path):
    """Linear RGB float32 (H, W, 3) from an EXR (OpenEXR >= 3 Python module, or Mitsuba)."""
    try:
        import OpenEXR
        ch = OpenEXR.File(path).channels()
        for k in ("RGBA", "RGB"):
            if k in ch:
                return np.asarray(ch[k].pixels[..., :3], dtype=np.float64)
        if all(k in ch for k in "RGB"):
            return np.stack([ch[k].pixels for k in "RGB"], -1).astype(np.float64)
        raise KeyError("no R, G, B channels in %s: %s" % (path, list(ch)))
    except ImportError:
        import mitsuba as mi
        mi.set_variant("scalar_rgb")
        bmp = mi.Bitmap(path)
        names = [bmp.struct_()[i].name for i in range(bmp.channel_count())]
        arr = np.array(bmp)
        return np.stack([arr[..., names.index(c)] for c in "RGB"], -1).astype(np.float64)


def relmse(a, b):
    return float(np.mean((a - b) ** 2 / (b ** 2 + 0.01)))


def mare(a, b):
    return float(np.mean(np.abs(a - b) / (np.abs(b) + 0.01)))


def luminance(x):
    return x[..., 0] * 0.2126 + x[..., 1] * 0.7152 + x[..., 2] * 0.0722


def tonemap(x, exposure):
    """Exposure (stops) and the sRGB transfer curve, clipped to [0, 1]."""
    v = np.clip(x * 2.0 ** exposure, 0.0, 1.0)
    return np.where(v <= 0.0031308, 12.92 * v, 1.055 * np.power(v, 1 / 2.4) - 0.055)


def flip_scores(ref, test, exposure):
    try:
        import flip_evaluator as flip
    except ImportError:
        return None
    _, hdr, _ = flip.evaluate(ref.astype(np.float32), test.astype(np.float32), "HDR",
                              applyMagma=False)
    _, ldr, _ = flip.evaluate(tonemap(ref, exposure).astype(np.float32),
                              tonemap(test, exposure).astype(np.float32), "LDR", applyMagma=False)
    return float(hdr), float(ldr)


def ssim_score(ref, test, exposure):
    try:
        from skimage.metrics import structural_similarity
    except ImportError:
        return None
    r = tonemap(ref, exposure)
    t = tonemap(test, exposure)
    return float(structural_similarity(r, t, channel_axis=2, data_range=1.0))


def pair_metrics(a, b, exposure, scale=None):
    """Metrics of a against reference b (optionally a scaled per channel first)."""
    if scale is not None:
        a = a * scale
    out = {
        "relMSE": relmse(a, b),
        "relMSE_rgb": [relmse(a[..., c], b[..., c]) for c in range(3)],
        "MARE": mare(a, b),
        "mean_ratio_rgb": [float(a[..., c].mean() / b[..., c].mean()) for c in range(3)],
    }
    f = flip_scores(b, a, exposure)
    if f:
        out["FLIP_HDR"], out["FLIP_LDR"] = f
    s = ssim_score(b, a, exposure)
    if s is not None:
        out["SSIM"] = s
    return out


def fit_scale(mira, ref, max_value=None):
    """Per channel s minimising sum (ref - s * mira)^2 over the pixels whose reference
    luminance is below max_value (None: all pixels). Directly seen lights are the same
    constant in both images and, being bright, would pin a plain fit to 1: leave them out."""
    keep = np.ones(ref.shape[:2], bool) if max_value is None else luminance(ref) < max_value
    return np.array([float((ref[keep, c] * mira[keep, c]).sum() / (mira[keep, c] ** 2).sum())
                     for c in range(3)])


# Regions as fractions of the image (x0, y0, x1, y1), top-left origin, for the seed Cornell
# box (iray_cornell_box.mi) seen from its own camera; check them in regions.png.
REGIONS = {
    "left_wall_red": (0.04, 0.25, 0.17, 0.70),
    "right_wall_green": (0.83, 0.25, 0.96, 0.70),
    "back_wall": (0.43, 0.23, 0.58, 0.40),
    "ceiling_front_of_light": (0.38, 0.085, 0.62, 0.11),
    "ceiling_behind_light": (0.38, 0.165, 0.62, 0.19),
    "light": (0.43, 0.125, 0.57, 0.15),
    "floor_centre": (0.24, 0.925, 0.47, 0.975),
    "floor_under_tall_block": (0.33, 0.860, 0.46, 0.890),
    "tall_block_front": (0.30, 0.47, 0.48, 0.78),
    "short_block_front": (0.50, 0.70, 0.74, 0.90),
}


def region_slices(shape):
    h, w = shape[:2]
    return {k: (slice(int(round(y0 * h)), int(round(y1 * h))), slice(int(round(x0 * w)), int(round(x1 * w))))
            for k, (x0, y0, x1, y1) in REGIONS.items()}


def save_png(arr, path, scale=1):
    from PIL import Image
    img = Image.fromarray((np.clip(arr, 0, 1) * 255 + 0.5).astype(np.uint8))
    if scale != 1:
        img = img.resize((img.width * scale, img.height * scale), Image.NEAREST)
    img.save(path)


def diverging(d):
    """d in [-1, 1] -> blue (negative) / white (0) / red (positive)."""
    d = np.clip(d, -1, 1)[..., None]
    white = np.ones(d.shape[:-1] + (3,))
    red = np.array([0.85, 0.1, 0.1])
    blue = np.array([0.1, 0.25, 0.9])
    return np.where(d > 0, white * (1 - d) + red * d, white * (1 + d) - blue * d)


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--mira", nargs="+", required=True, help="one or two mira EXRs (different seeds)")
    p.add_argument("--ref", nargs="+", required=True, help="one or two reference EXRs (different seeds)")
    p.add_argument("--outdir", help="where the PNGs and metrics.json go")
    p.add_argument("--exposure", type=float, default=1.0, help="stops, for the PNGs and LDR metrics")
    p.add_argument("--labels", nargs=2, default=["mira", "mitsuba"])
    p.add_argument("--scale-max", type=float, default=1.0,
                   help="fit the per-channel scale over pixels with reference luminance below this "
                        "(default 1: leaves out directly seen lights); negative: all pixels")
    args = p.parse_args()
    if args.scale_max is not None and args.scale_max < 0:
        args.scale_max = None

    M = [load_exr(f) for f in args.mira]
    R = [load_exr(f) for f in args.ref]
    for x in M + R:
        if x.shape != M[0].shape:
            sys.exit("images differ in size")
    lm, lr = args.labels
    res = {"files": {"mira": args.mira, "ref": args.ref}}

    scale = fit_scale(M[0], R[0], args.scale_max)
    res["scale_fit_max_ref_luminance"] = args.scale_max
    res["scale_ref_over_mira_rgb"] = scale.tolist()
    res["scale_ref_over_mira_rgb_all_pixels"] = fit_scale(M[0], R[0]).tolist()
    if len(M) > 1 and len(R) > 1:
        res["scale_ref_over_mira_rgb_seed_avg"] = fit_scale((M[0] + M[1]) / 2, (R[0] + R[1]) / 2,
                                                            args.scale_max).tolist()

    res["%s_vs_%s" % (lm, lr)] = pair_metrics(M[0], R[0], args.exposure)
    res["%s_vs_%s_scaled" % (lm, lr)] = pair_metrics(M[0], R[0], args.exposure, scale)
    if len(M) > 1 and len(R) > 1:
        res["%s_vs_%s_second_seeds" % (lm, lr)] = pair_metrics(M[1], R[1], args.exposure)
    if len(M) > 1:
        res["%s_vs_%s" % (lm, lm)] = pair_metrics(M[1], M[0], args.exposure)
    if len(R) > 1:
        res["%s_vs_%s" % (lr, lr)] = pair_metrics(R[1], R[0], args.exposure)
    if len(M) > 1 and len(R) > 1:
        expected = (res["%s_vs_%s" % (lm, lm)]["relMSE"] + res["%s_vs_%s" % (lr, lr)]["relMSE"]) / 2
        res["relMSE_expected_from_noise"] = expected
        # Averages of the two seeds: half the noise each; a bias would stay.
        ma, ra = (M[0] + M[1]) / 2, (R[0] + R[1]) / 2
        res["avg2_%s_vs_avg2_%s" % (lm, lr)] = {"relMSE": relmse(ma, ra), "MARE": mare(ma, ra),
                                                 "relMSE_expected_from_noise": expected / 2}

    # Regions: means, and the standard error of the difference of the means estimated from
    # the seed pairs (per-pixel variance ~ (x1 - x2)^2 / 2, pixels independent).
    regions = {}
    for name, (ys, xs) in region_slices(M[0].shape).items():
        r = {}
        mm = np.mean([m[ys, xs].reshape(-1, 3).mean(0) for m in M], 0)
        rm = np.mean([x[ys, xs].reshape(-1, 3).mean(0) for x in R], 0)
        r["pixels"] = int(M[0][ys, xs].shape[0] * M[0][ys, xs].shape[1])
        r[lm] = mm.tolist()
        r[lr] = rm.tolist()
        r["ratio_%s_over_%s" % (lm, lr)] = (mm / rm).tolist()
        if len(M) > 1 and len(R) > 1:
            n = r["pixels"]
            var_m = ((M[0][ys, xs] - M[1][ys, xs]) ** 2 / 2).reshape(-1, 3).sum(0) / n ** 2 / len(M)
            var_r = ((R[0][ys, xs] - R[1][ys, xs]) ** 2 / 2).reshape(-1, 3).sum(0) / n ** 2 / len(R)
            se = np.sqrt(var_m + var_r)
            # Noise-free regions (a light's inside): no z; see the ratio instead.
            with np.errstate(divide="ignore", invalid="ignore"):
                z = np.where(se > 0, (mm - rm) / np.where(se > 0, se, 1), np.nan)
            r["z_rgb"] = [None if np.isnan(v) else float(v) for v in z]
        regions[name] = r
    res["regions"] = regions

    # Ratio of the image means over the same pixels (unbiased by noise, unlike the least-
    # squares scale, which noise in the mira image pulls below 1 by about its relMSE).
    keep = np.ones(R[0].shape[:2], bool) if args.scale_max is None else luminance(R[0]) < args.scale_max
    mm = np.mean([m[keep].mean(0) for m in M], 0)
    rm = np.mean([x[keep].mean(0) for x in R], 0)
    res["mean_ratio_%s_over_%s_rgb" % (lr, lm)] = (rm / mm).tolist()
    if len(M) > 1 and len(R) > 1:
        n = keep.sum()
        var = (((M[0][keep] - M[1][keep]) ** 2 / 2).sum(0) / len(M) + ((R[0][keep] - R[1][keep]) ** 2 / 2).sum(0) / len(R)) / n ** 2
        res["mean_ratio_se_rgb"] = (np.sqrt(var) / mm).tolist()

    # Low-frequency bias test: means of BxB pixel blocks (luminance), difference over its
    # standard error (from the seed pairs); for pure noise, mean(z^2) ~= 1 and |z| > 4 is
    # rare. Noise-free blocks (inside a light) are left out.
    if len(M) > 1 and len(R) > 1:
        lM = [luminance(m) for m in M]
        lR = [luminance(x) for x in R]
        h, w = lM[0].shape
        blocks = {}
        for B in (4, 16):
            hb, wb = h // B, w // B
            cut = lambda x: x[:hb * B, :wb * B].reshape(hb, B, wb, B)
            dm = cut((lM[0] + lM[1]) / 2 - (lR[0] + lR[1]) / 2).mean((1, 3))
            vm = (cut((lM[0] - lM[1]) ** 2 / 2).sum((1, 3)) + cut((lR[0] - lR[1]) ** 2 / 2).sum((1, 3))) / (B * B) ** 2 / 2
            ok = vm > 0
            z = dm[ok] / np.sqrt(vm[ok])
            blocks["%dx%d" % (B, B)] = {"blocks": int(ok.sum()), "mean_z2": float(np.mean(z ** 2)),
                                        "mean_z": float(np.mean(z)), "max_abs_z": float(np.max(np.abs(z))),
                                        "frac_abs_z_gt_3": float(np.mean(np.abs(z) > 3))}
        res["block_z"] = blocks

    # Text report.
    def line(k, v):
        extra = "".join("  %s %.4f" % (m, v[m]) for m in ("FLIP_HDR", "FLIP_LDR", "SSIM") if m in v)
        print("%-34s relMSE %.3e  MARE %.4f%s" % (k, v["relMSE"], v["MARE"], extra))
    print("scale (%s ~= s * %s), per channel, pixels with %s luminance < %g: %s"
          % (lr, lm, lr, args.scale_max, " ".join("%.5f" % s for s in scale)))
    if "scale_ref_over_mira_rgb_seed_avg" in res:
        print("  same, both seeds averaged: %s" % " ".join("%.5f" % s for s in res["scale_ref_over_mira_rgb_seed_avg"]))
    print("  all pixels (lights included): %s" % " ".join("%.5f" % s for s in res["scale_ref_over_mira_rgb_all_pixels"]))
    k = "mean_ratio_%s_over_%s_rgb" % (lr, lm)
    print("ratio of image means (%s / %s, same pixels, all seeds): %s%s" % (
        lr, lm, " ".join("%.5f" % v for v in res[k]),
        ("  (standard error %s)" % " ".join("%.5f" % v for v in res["mean_ratio_se_rgb"])) if "mean_ratio_se_rgb" in res else ""))
    for k, v in res.items():
        if isinstance(v, dict) and "relMSE" in v and "MARE" in v and k != "regions":
            line(k, v)
    if "relMSE_expected_from_noise" in res:
        print("relMSE expected from noise alone (mean of the two same-renderer values): %.3e"
              % res["relMSE_expected_from_noise"])
    for k, b in res.get("block_z", {}).items():
        print("block means %-6s %4d blocks: mean z^2 %.3f (1 = pure noise), mean z %+.3f, max |z| %.2f, |z|>3: %.2f %%"
              % (k, b["blocks"], b["mean_z2"], b["mean_z"], b["max_abs_z"], 100 * b["frac_abs_z_gt_3"]))
    print("\nregion means (both seeds averaged), %s / %s, z = difference / its standard error" % (lm, lr))
    for name, r in regions.items():
        z = r.get("z_rgb")
        print("  %-24s %s (%s) vs (%s)  ratio %s%s" % (
            name, "%5d px" % r["pixels"],
            " ".join("%.5g" % v for v in r[lm]), " ".join("%.5g" % v for v in r[lr]),
            " ".join("%.5f" % v for v in r["ratio_%s_over_%s" % (lm, lr)]),
            ("  z " + " ".join("n/a" if v is None else "%+.1f" % v for v in z)) if z else ""))

    if args.outdir:
        os.makedirs(args.outdir, exist_ok=True)
        with open(os.path.join(args.outdir, "metrics.json"), "w") as f:
            json.dump(res, f, indent=1)
        ma = np.mean(M, 0)
        ra = np.mean(R, 0)
        # Signed luminance difference, in units of its noise (when two seeds of each).
        d = luminance(ma) - luminance(ra)
        if len(M) > 1 and len(R) > 1:
            sig = np.sqrt(((luminance(M[0]) - luminance(M[1])) ** 2 / 2) / len(M)
                          + ((luminance(R[0]) - luminance(R[1])) ** 2 / 2) / len(R))
            # Per-pixel sigma from 2 samples is itself noisy: smooth it with a 5x5 box.
            from numpy.lib.stride_tricks import sliding_window_view
            pad = np.pad(sig ** 2, 2, mode="edge")
            sig = np.sqrt(sliding_window_view(pad, (5, 5)).mean((-1, -2)))
            # Noise-free pixels (inside a light): compare to float precision instead.
            sig = np.maximum(sig, 1e-5 * np.abs(luminance(ra)) + 1e-9)
            dn = d / np.maximum(sig, 1e-12) / 4.0  # +-4 sigma -> full colour
            note = "signed luminance difference / noise sigma, full colour at +-4 sigma"
        else:
            dn = d / (np.abs(luminance(ra)) + 0.01) / 0.1  # +-10 % -> full colour
            note = "signed relative luminance difference, full colour at +-10 %"
        diff = diverging(dn)
        save_png(diff, os.path.join(args.outdir, "diff.png"), 2)
        tm, tr = tonemap(ma, args.exposure), tonemap(ra, args.exposure)
        gap = np.ones((tm.shape[0], 4, 3))
        save_png(np.concatenate([tm, gap, tr, gap, diff], 1), os.path.join(args.outdir, "side_by_side.png"), 2)
        box = tm.copy()
        for name, (ys, xs) in region_slices(tm.shape).items():
            for yy in (ys.start, ys.stop - 1):
                box[yy, xs] = [1, 1, 0]
            for xx in (xs.start, xs.stop - 1):
                box[ys, xx] = [1, 1, 0]
        save_png(box, os.path.join(args.outdir, "regions.png"), 2)
        print("\nwrote %s/{side_by_side,diff,regions}.png, metrics.json (%s | %s | %s)"
              % (args.outdir, lm, lr, note))


if __name__ == "__main__":
    main()
