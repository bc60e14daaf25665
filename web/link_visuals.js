// What the robot looks like, from the module (robot.links: the URDF's links and visuals as
// achd's loader reads them; the page parses no URDF of its own once a robot is loaded):
// the visuals the view can draw, grouped by the link frame forward kinematics moves them
// with, and why any other was left out. Colours outside [0, 1] are clamped.

// robot: an achd robot. -> {frames: [{fk: index in [root, ...linkNames], offset: the
// link's pose in that frame ({position, rotation}, null: the frame's own link), link
// (name), visuals: [{position, rotation, geometry, color}]}], problems: ['link "arm",
// visual 2: cylinder radius "-0.02" is not a positive number', ...]}
export function linkVisuals(robot) {
  const frames = [];
  const problems = [];
  for (const link of robot.links) {
    const visuals = [];
    link.visuals.forEach((visual, k) => {
      const why = undrawable(visual.geometry);
      if (why) problems.push(`link "${link.name}", visual ${k + 1}: ${why}`);
      else visuals.push({ ...visual, color: visual.color && visual.color.map((v) => Math.min(Math.max(v, 0), 1)) });
    });
    if (visuals.length) frames.push({ fk: link.frame, offset: link.offset, link: link.name, visuals });
  }
  return { frames, problems };
}

// Why three cannot draw a geometry, or null.
function undrawable(g) {
  const positive = (name, v) => (v > 0 ? null : `${g.type} ${name} "${v}" is not a positive number`);
  switch (g.type) {
    case 'box':
      return g.size.some((s) => !(s > 0)) ? `box size "${g.size.join(' ')}" has a side that is not positive` : null;
    case 'cylinder':
      return positive('radius', g.radius) ?? positive('length', g.length);
    case 'sphere':
      return positive('radius', g.radius);
    case 'mesh':
      return g.filename ? null : 'mesh without a filename';
    default:
      return `geometry "${g.type}" is not box, cylinder, sphere or mesh`;
  }
}

// Each link's URDF parent link, Map<link name, parent name>, over robot.links (the root
// has none).
export function linkParents(robot) {
  return new Map(robot.links.filter((l) => l.parent !== null).map((l) => [l.name, l.parent]));
}
