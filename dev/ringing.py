#!/usr/bin/python3
"""The ringing of a run recorded at every step (`--set record_every=1`): the
spectrum of the load after its peak, its rms distance from its running mean
over one fundamental period, what a record every N steps (the default
interval) shows of it, the power above that record's Nyquist frequency, and
the load cell's peak for windows of given lengths (results/dynamics/ringing.md).

    /usr/bin/python3 dev/ringing.py RUN_DIR [RUN_DIR ...] [--windows 0.1e-3,0.25e-3,...]
"""
import csv, json, sys
import numpy as np

def load(out):
    rows = list(csv.DictReader(open(out + "/curve.csv")))
    s = json.load(open(out + "/summary.json"))
    t = np.array([float(r["time_s"]) for r in rows]); F = np.array([float(r["stress_MPa"]) for r in rows])
    e = np.array([float(r["mean_strain"]) for r in rows])
    return t, F, e, s

def running_mean(F, n):
    c = np.cumsum(np.concatenate([[0.0], F]))
    m = np.full_like(F, np.nan); h = n // 2
    m[h:len(F) - h] = (c[n:] - c[:-n])[: len(F) - 2 * h] / n
    return m

def analyse(out, strain_stop=None):
    t, F, e, s = load(out)
    dt = s["dt_s"]; w1 = s["omega1_rad_s"]; wmax = s["omega_max_rad_s"]
    T1 = 2 * np.pi / w1; n1 = int(round(T1 / dt)) | 1
    ip = int(np.argmax(F)); peak = F[ip]
    m = running_mean(F, n1)
    post = slice(ip, len(F) if strain_stop is None else np.searchsorted(e, strain_stop))
    r = (F - m)[post]; ok = ~np.isnan(r); r = r[ok]
    rms = np.sqrt(np.mean(r ** 2)) / peak
    f = np.fft.rfftfreq(len(r), dt); P = np.abs(np.fft.rfft(r * np.hanning(len(r)))) ** 2
    fmax = wmax / 2 / np.pi
    bands = [(0, 700), (700, 3000), (3000, 12000), (12000, 1e12)]
    frac = [P[(f >= a) & (f < b)].sum() / P.sum() for a, b in bands]
    top = f[np.argsort(P)[-5:][::-1]]
    # a record every N steps: one step's sample against the load cell's mean over the N steps
    pp = s["parameters"]["parameters"]; N = max(1, int((pp["eps_p"] / 50) / (pp["strain_rate"] * dt)))
    sample = F[N - 1::N]; cell = F[: len(F) // N * N].reshape(-1, N).mean(axis=1)
    mk = running_mean(F, n1)[N - 1::N][: len(cell)]
    def rms_rec(x):
        d = (x[: len(mk)] - mk)[ip // N:]; d = d[~np.isnan(d)]; return np.sqrt(np.mean(d ** 2)) / peak
    mavg = np.nanmax(m)
    print(f"{out}: peak {peak*1e3:.3f} kN (step {ip}), max of the T1 running mean {mavg*1e3:.3f} kN ({(mavg/peak-1)*100:+.1f} %), "
          f"T1 {T1*1e3:.2f} ms = {n1} steps, f_max {fmax/1e3:.1f} kHz")
    print(f"  after the peak: rms(F - mean over T1) = {rms*100:.2f} % of the peak; power <0.7 / 0.7-3 / 3-12 / >12 kHz: "
          + " / ".join(f"{x*100:.0f} %" for x in frac) + f"; strongest lines {', '.join(f'{x/1e3:.2f}' for x in top)} kHz")
    print(f"  a record every N = {N} steps: sampled rms {rms_rec(sample)*100:.2f} %, load cell rms {rms_rec(cell)*100:.2f} %; "
          f"largest sample {sample.max()*1e3:.3f} kN, largest cell {cell.max()*1e3:.3f} kN")


def windows(out, times):
    t, F, e, s = load(out)
    dt = s["dt_s"]; T1 = 2 * np.pi / s["omega1_rad_s"]; n1 = int(round(T1 / dt)) | 1
    ip = int(np.argmax(F))
    for w in times:
        N = max(1, int(round(w / dt)))
        cell = F[: len(F) // N * N].reshape(-1, N).mean(axis=1)
        m = running_mean(F, n1)[N - 1::N][: len(cell)]
        kp = int(np.argmax(cell)); d = (cell - m)[kp:]; d = d[~np.isnan(d)]
        print(f"  {out} window {w*1e3:.2f} ms ({N} steps): load-cell peak {cell.max()*1e3:.3f} kN, "
              f"rms after it from the T1 mean {np.sqrt(np.mean(d**2))/cell.max()*100:.2f} %")


def aliased(out):
    """The share of the post-peak residual's power above the record's Nyquist
    frequency, sampled (one step a record) and through the load cell (the mean
    over the record's N steps: |H|^2 = (sin(N x)/(N sin x))^2, x = pi f dt)."""
    t, F, e, s = load(out)
    dt = s["dt_s"]; pp = s["parameters"]["parameters"]
    N = max(1, int((pp["eps_p"] / 50) / (pp["strain_rate"] * dt)))
    n1 = int(round(2 * np.pi / s["omega1_rad_s"] / dt)) | 1
    ip = int(np.argmax(F)); r = (F - running_mean(F, n1))[ip:]; r = r[~np.isnan(r)]
    f = np.fft.rfftfreq(len(r), dt); P = np.abs(np.fft.rfft(r)) ** 2
    x = np.pi * f * dt; H = np.ones_like(f); nz = x > 0; H[nz] = (np.sin(N * x[nz]) / (N * np.sin(x[nz]))) ** 2
    fN = 1 / (2 * N * dt)
    print(f"  {out}: record every {N} steps, Nyquist {fN / 1e3:.2f} kHz: power above it {P[f > fN].sum() / P.sum():.0%}"
          f" sampled, {(P * H)[f > fN].sum() / P.sum():.1%} through the load cell")


if __name__ == "__main__":
    import argparse
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("runs", nargs="+")
    ap.add_argument("--windows", default="1e-4,2.5e-4,5e-4,1e-3,2e-3", help="load-cell windows [s], comma-separated")
    a = ap.parse_args()
    for out in a.runs:
        analyse(out)
        aliased(out)
        windows(out, [float(w) for w in a.windows.split(",")])
