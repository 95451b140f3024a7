#!/usr/bin/env bash
# Two builds on one host: .dev/meshvol-old against .dev/meshvol-new (stripped release
# binaries), at 16 threads: `check` and checked `volume` of a 5M-triangle UV sphere and
# `grid --no-check` of a 1M one on 512³ (three rounds, the builds interleaved), then
# `check` of 20M triangles twice each; wall seconds and peak memory of each run.
# .dev/sphere is target/release/examples/sphere. Needs bash and python3.
set -u
d=/tmp/cmp; mkdir -p $d
S=.dev/sphere
[ -s $d/5m.stl ] || $S 5000000 $d/5m.stl >/dev/null
[ -s $d/1m.stl ] || $S 1000000 $d/1m.stl >/dev/null
peak() { python3 -c "import resource,subprocess,sys,time; t=time.time(); subprocess.run(sys.argv[2:],stdout=subprocess.DEVNULL); print(sys.argv[1], round(time.time()-t,3), 's', round(resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss/1024), 'MB')" "$@"; }
for r in 1 2 3; do
  for b in old new; do
    peak "$b check 5M t16" .dev/meshvol-$b --threads 16 check $d/5m.stl
    peak "$b volume 5M t16" .dev/meshvol-$b --threads 16 volume $d/5m.stl
    peak "$b grid512 1M t16" .dev/meshvol-$b --threads 16 grid $d/1m.stl --cells 512,512,512 --no-check
  done
done
$S 20000000 $d/20m.stl >/dev/null
for b in old new old new; do peak "$b check 20M t16" .dev/meshvol-$b --threads 16 check $d/20m.stl; done
