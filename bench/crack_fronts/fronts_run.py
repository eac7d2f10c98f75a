"""Shared by the crack-front benchmarks: write a scene, run it with cleave, read its crack_fronts.csv."""
import csv, json, pathlib, subprocess, time


def run_scene(cleave, scene, out, threads=""):
    """Runs scene (a dict) in out/run; returns (rows of crack_fronts.csv, sorted output times, wall s)."""
    out = pathlib.Path(out)
    out.mkdir(parents=True, exist_ok=True)
    (out / "scene.json").write_text(json.dumps(scene, indent=1))
    cmd = [cleave, "run", str(out / "scene.json"), "--out", str(out / "run"), "--quiet"]
    if threads:
        cmd += ["--threads", threads]
    t0 = time.time()
    subprocess.run(cmd, check=True)
    wall = time.time() - t0
    rows = list(csv.DictReader(open(out / "run/crack_fronts.csv")))
    return rows, sorted({float(r["time_s"]) for r in rows}), wall
