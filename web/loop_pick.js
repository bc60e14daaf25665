// The loop joint two picked links close: a fixed loop joint whose frame a is link_a's own
// frame and whose frame b is where link_a's frame is now, in link_b's frame, so that the
// two frames coincide at this instant and the loop is closed when it starts.

// links: every link's pose now ({name, position, rotation: 9 numbers, row-major}, the
// root's included: web/simulation.js links()); taken: the loop names in use. Returns the
// loop as loadURDF's loops option takes it.
export function fixedLoopBetween(links, linkA, linkB, taken) {
  const a = links.find((l) => l.name === linkA);
  const b = links.find((l) => l.name === linkB);
  if (!a) throw new Error(`no link "${linkA}"`);
  if (!b) throw new Error(`no link "${linkB}"`);
  const Rb = b.rotation;
  // frame a in frame b: p = Rb^T (pa - pb), R = Rb^T Ra
  const d = [0, 1, 2].map((i) => a.position[i] - b.position[i]);
  const xyz = [0, 1, 2].map((j) => Rb[j] * d[0] + Rb[3 + j] * d[1] + Rb[6 + j] * d[2]);
  const R = [0, 1, 2].flatMap((i) => [0, 1, 2].map((j) =>
    Rb[i] * a.rotation[j] + Rb[3 + i] * a.rotation[3 + j] + Rb[6 + i] * a.rotation[6 + j]));
  let name = `${linkA}-${linkB}`;
  for (let k = 2; taken.has(name); k++) name = `${linkA}-${linkB}-${k}`;
  return { name, type: 'fixed', link_a: linkA, origin_a: { xyz: [0, 0, 0], rpy: [0, 0, 0] },
    link_b: linkB, origin_b: { xyz, rpy: rollPitchYaw(R) } };
}

// URDF's rpy of a rotation matrix (row-major): R = Rz(yaw) Ry(pitch) Rx(roll).
export function rollPitchYaw(R) {
  const roll = Math.atan2(R[7], R[8]);
  const pitch = Math.atan2(-R[6], Math.hypot(R[7], R[8]));
  const yaw = Math.atan2(R[3], R[0]);
  return [roll, pitch, yaw];
}
