#!/bin/sh
# Runs inside the cgroup-v2-only VM that scripts/cgroup2_vm.py boots (as root, its
# root file system the host's, read-only over 9p).
#
# usage: guest.sh OUT PYTHON REPO STEPS...     STEPS: env, probe, class, pytest
#   env     the cgroup mounts and controllers (must be cgroup2 alone)
#   probe   Hierarchy.prepare/group/release on the real kernel, in a delegated group
#   class   grade the hand-made class (scripts/cgroup2_vm/make_class.py) in a delegated
#           group, a monitor recording each submission group's cgroup files
#   pytest  the grader's integration tests (WT_VM_PYTEST: their node ids / -k)
# Writes OUT/<step>.* and OUT/<step>.rc; exits 0 when every step passed.
set -u
OUT=$1 PY=$2 REPO=$3
shift 3
CG=/sys/fs/cgroup
export PYTHONDONTWRITEBYTECODE=1 PYTHONHASHSEED=0 HOME=/tmp/home
# the package of REPO, whatever folder the editable install points at
export PYTHONPATH=$REPO
mkdir -p "$HOME"

# the Python prefix and the repository again, with the guest's page cache (cache=loose):
# the 9p root has none, and under emulation every import would go to the host
PREFIX=$($PY -c 'import sys; print(sys.prefix)')
mount -t 9p -o trans=virtio,version=9p2000.L,cache=loose,ro,msize=512000 wtpy "$PREFIX" \
    || echo "guest: no cached mount of $PREFIX (slower)"
mount -t 9p -o trans=virtio,version=9p2000.L,cache=loose,ro,msize=512000 wtrepo "$REPO" \
    || echo "guest: no cached mount of $REPO (slower)"
cd "$REPO" || exit 3
# a /tmp of the VM's own (virtme-ng's is an overlay on the host's /tmp, where other
# graders' temporary folders would be seen as left by this one)
mount -t tmpfs -o mode=1777 wt-tmp /tmp && mkdir -p "$HOME"

failed=0
step() { echo "$2" > "$OUT/$1.rc"; [ "$2" = 0 ] || failed=1; echo "guest: $1 -> $2"; }

# a delegated group holding one process (as systemd-run --scope -p Delegate=yes gives):
# the root group hands its controllers down, the group itself enables none
delegate() {
    echo "+memory +pids +cpu +io" > $CG/cgroup.subtree_control
    mkdir -p "$CG/$1"
}

for s in "$@"; do
    case $s in
    env)
        {
            echo "## uname -r"; uname -r
            echo "## /proc/cmdline"; cat /proc/cmdline
            echo "## cgroup lines of /proc/self/mountinfo"; grep -E ' - cgroup2? ' /proc/self/mountinfo
            echo "## /proc/cgroups"; cat /proc/cgroups
            echo "## /proc/self/cgroup"; cat /proc/self/cgroup
            echo "## $CG/cgroup.controllers"; cat $CG/cgroup.controllers
            echo "## nproc, memory"; nproc; grep MemTotal /proc/meminfo
        } > "$OUT/env.txt" 2>&1
        # cgroup v2 only: one cgroup2 mount, no v1 mount, no controller on a v1 hierarchy
        v1=$(grep -c ' - cgroup ' /proc/self/mountinfo)
        v2=$(grep -c ' - cgroup2 ' /proc/self/mountinfo)
        bound=$(awk 'NR > 1 && $2 != 0' /proc/cgroups | wc -l)
        have=$(cat $CG/cgroup.controllers)
        ok=0
        [ "$v1" = 0 ] && [ "$v2" = 1 ] && [ "$bound" = 0 ] || ok=1
        for c in memory pids cpu; do
            case " $have " in *" $c "*) ;; *) ok=1 ;; esac
        done
        echo "v1 mounts $v1, cgroup2 mounts $v2, controllers on v1 hierarchies $bound" >> "$OUT/env.txt"
        step env $ok
        ;;
    probe)
        delegate wt-probe
        sh -c "echo \$\$ > $CG/wt-probe/cgroup.procs && exec $PY scripts/cgroup2_vm/probe.py" \
            > "$OUT/probe.txt" 2>&1
        step probe $?
        rmdir $CG/wt-probe 2>/dev/null
        ;;
    class)
        delegate wt-class
        rm -rf /tmp/wt-class && $PY scripts/cgroup2_vm/make_class.py /tmp/wt-class > /dev/null
        $PY scripts/cgroup2_vm/monitor.py $CG "$OUT/class-groups.json" &
        mon=$!
        start=$(date +%s)
        # the grader alone in its delegated group: it must move itself into a leaf
        sh -c "echo \$\$ > $CG/wt-class/cgroup.procs && exec $PY scripts/cgroup2_vm/grade_scaled.py grade \
            --out $OUT/class.csv --feedback $OUT/class-feedback --memory 1000 --cpus 1 \
            --timeout ${WT_VM_TIMEOUT:-1500} --cell-timeout ${WT_VM_TIMEOUT:-1500} --quiet \
            /tmp/wt-class" > "$OUT/class.stdout" 2> "$OUT/class.stderr"
        rc=$?
        echo "grade exit status $rc after $(( $(date +%s) - start )) s" >> "$OUT/class.stdout"
        sleep 2
        kill -TERM $mon; wait $mon
        {
            echo "## wt-grade-* groups left under $CG:"
            find $CG -name 'wt-grade-*'
            echo "## processes left with WHITTAKER_TEACH_RUN in their environment:"
            grep -l WHITTAKER_TEACH_RUN /proc/[0-9]*/environ 2>/dev/null
            echo "## processes left of the sandbox uids (61000-61063):"
            ps -eo uid=,pid=,args= | awk '$1 >= 61000 && $1 < 61064'
            echo "## $CG/wt-class: cgroup.procs, cgroup.subtree_control (given back?)"
            cat $CG/wt-class/cgroup.procs; cat $CG/wt-class/cgroup.subtree_control
            echo "## temporary folders left in /tmp:"
            ls -d /tmp/wt-grade-* 2>/dev/null
        } > "$OUT/class-after.txt" 2>&1
        $PY scripts/cgroup2_vm/check_class.py "$OUT" > "$OUT/class-check.txt" 2>&1
        step class $?
        rmdir $CG/wt-class 2>/dev/null
        ;;
    pytest)
        delegate wt-pytest
        # shellcheck disable=SC2086
        # (wt_vm_timescale: the grader's timeouts x WT_VM_TIME_SCALE, for an emulated CPU)
        PYTHONPATH=$REPO/scripts/cgroup2_vm:$REPO sh -c "echo \$\$ > $CG/wt-pytest/cgroup.procs && \
            exec $PY -m pytest -q -p no:randomly -p no:cacheprovider -p wt_vm_timescale \
            -rA ${WT_VM_PYTEST:-tests/integration/test_grade.py}" \
            > "$OUT/pytest.txt" 2>&1
        step pytest $?
        {
            echo "## wt-grade-* groups left under $CG:"; find $CG -name 'wt-grade-*'
        } > "$OUT/pytest-after.txt" 2>&1
        ;;
    *)
        echo "guest: unknown step $s"; failed=1 ;;
    esac
done
exit $failed
