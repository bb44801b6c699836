#!/bin/bash
# dask scaling of `tilekit search k-uniform --k K` with a separate scheduler and W workers
K=${K:-5}
cd "${OUT:-.}"
V=$(dirname "$(command -v tilekit)")
PORT=$(python3 -c "import socket;s=socket.socket();s.bind(('127.0.0.1',0));print(s.getsockname()[1])")
nice -n 10 $V/dask scheduler --host 127.0.0.1 --port $PORT --no-dashboard > sched.log 2>&1 &
SCHED=$!
sleep 8
cpu() { awk '{print $14+$15}' /proc/$1/stat; }
for W in ${WS:-1 2 4}; do
  PIDS=""
  for i in $(seq $W); do
    nice -n 10 $V/dask worker tcp://127.0.0.1:$PORT --nworkers 1 --nthreads 1 --no-nanny --no-dashboard --name w$W-$i > worker$W-$i.log 2>&1 &
    PIDS="$PIDS $!"
  done
  sleep 10
  B=0; for p in $PIDS; do B=$((B + $(cpu $p))); done
  rm -f d$K-$W.sqlite
  echo "W=$W start $(date -u +%H:%M:%S) $(uptime)"
  nice -n 10 /usr/bin/time -f "client wall %e s user %U sys %S maxrss %M KB" $V/tilekit --catalogue sqlite:///$PWD/d$K-$W.sqlite search k-uniform --k $K --executor dask --scheduler tcp://127.0.0.1:$PORT 2>&1 | tail -4
  A=0; for p in $PIDS; do A=$((A + $(cpu $p))); done
  echo "W=$W end $(date -u +%H:%M:%S) $(uptime); worker CPU $(( (A - B) / 100 )) s (ticks $((A-B)))"
  for p in $PIDS; do kill $p; done
  sleep 3
done
kill $SCHED
