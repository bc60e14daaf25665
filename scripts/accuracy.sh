#!/bin/sh
# Regenerates the accuracy-versus-time study that docs/guide/accuracy-cost.md embeds: builds the Release
# CLI (build/, or $ACHD_ACCURACY_BUILD; -ffp-contract=off as every measured build) and runs
# `achd accuracy` on the damped arm and the 50-link chain (2 s), the undamped arm (0.5 s: its spinning wrist makes later states too sensitive for a converged reference)
# and the stiff dual-arm torso (0.2 s: it settles by then), writing docs/accuracy/<name>/accuracy.{csv,json,svg}.
#   scripts/accuracy.sh            # from the repository root
set -eu
cd "$(dirname "$0")/.."
build=${ACHD_ACCURACY_BUILD:-build}
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$build" -j2 --target achd_cli
for pair in arm7:robots/scenes/kuka_lwr4_hold_z_rx.json arm7_undamped:robots/scenes/kuka_lwr4_undamped_hold_z_rx.json \
    chain50:robots/scenes/chain50_fall.json torso_stiff:robots/scenes/dual_arm_torso_stiff_hold.json; do
  name=${pair%%:*}
  scene=${pair#*:}
  echo "accuracy: $scene -> docs/accuracy/$name/" >&2
  "$build/achd" accuracy "$scene" --out "docs/accuracy/$name" >/dev/null
done
