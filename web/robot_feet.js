// The feet an own floating robot stands on: the leaf links (no link hangs from them)
// lowest in z at its start pose, those within FOOT_SPREAD of the lowest. A quadruped's
// four feet and a humanoid's two soles are level in the poses their SRDFs name.

// Leaves this close (m) to the lowest count as feet too.
export const FOOT_SPREAD = 0.01;

// robot: an achd robot (links, linkNames, forwardKinematics); q: the start pose (the free
// joint's 7 numbers first). -> link names, in the robot's link order.
export function lowestLeaves(robot, q) {
  const parents = new Set(robot.links.map((l) => l.parent));
  const leaves = new Set(robot.linkNames.filter((l) => !parents.has(l)));
  const heights = robot.forwardKinematics(q).filter((l) => leaves.has(l.name));
  if (!heights.length) return [];
  const lowest = Math.min(...heights.map((l) => l.position[2]));
  return heights.filter((l) => l.position[2] <= lowest + FOOT_SPREAD).map((l) => l.name);
}
