#!/usr/bin/env bash
# `check` of a 5M-triangle UV sphere at 16 threads, .dev/meshvol-old and .dev/meshvol-new
# interleaved (five runs each), then the new build at 1 thread (three runs) and its
# stage timings at 16. Wall seconds of each run. .dev/sphere: the sphere example.
set -u
d=/tmp/cmp; mkdir -p $d
S=.dev/sphere
[ -s $d/5m.stl ] || $S 5000000 $d/5m.stl >/dev/null
t() { python3 -c "import subprocess,sys,time; t=time.time(); subprocess.run(sys.argv[2:],stdout=subprocess.DEVNULL); print(sys.argv[1], round(time.time()-t,3), 's')" "$@"; }
for r in 1 2 3 4 5; do for b in old new; do t "$b check 5M t16" .dev/meshvol-$b --threads 16 check $d/5m.stl; done; done
for r in 1 2 3; do t "new check 5M t1" .dev/meshvol-new --threads 1 check $d/5m.stl; done
.dev/meshvol-new --threads 16 -q --timings check $d/5m.stl --json | tail -n 1 | python3 -c "import json,sys; j=json.loads(sys.stdin.read()); print(', '.join('%s %.3f/%.3f'%(s['stage'],s['wall_s'],s['cpu_s']) for s in j['timings']))"
