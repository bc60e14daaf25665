// What a URDF says a robot looks like, read with the browser's XML parser: per link its
// <visual> elements (box, cylinder, sphere, or a mesh file with a scale), each with its
// origin in the link frame and its colour (a <material> given inline or by name at the
// robot's top level), and every joint's origin and axis, which place the links that
// forward kinematics does not list (a chain's side links). achd does not use <visual>; a visual
// that cannot be read is left out and named in `problems`, the robot still loads.

// -> {visuals: Map<link name, Visual[]>, joints: Map<child link, Joint>, problems: string[]}
//   Visual: {link, xyz, rpy, geometry, color: [r, g, b, a] or null}
//   geometry: {type: 'box', size} | {type: 'cylinder', radius, length} |
//             {type: 'sphere', radius} | {type: 'mesh', filename, scale}
//   Joint: {name, type, parent, xyz, rpy, axis}
export function urdfVisuals(text) {
  const doc = new DOMParser().parseFromString(text, 'application/xml');
  const robot = doc.documentElement;
  if (doc.querySelector('parsererror') || robot.nodeName !== 'robot') {
    throw new Error('not a URDF file: expected an XML document whose root element is <robot>');
  }
  const problems = [];
  const namedColors = new Map();
  for (const e of robot.children) {
    if (e.nodeName !== 'material') continue;
    const color = readColor(e);
    if (color) namedColors.set(e.getAttribute('name'), color);
  }

  const visuals = new Map();
  for (const link of robot.children) {
    if (link.nodeName !== 'link') continue;
    const name = link.getAttribute('name');
    const list = [];
    [...link.children].filter((e) => e.nodeName === 'visual').forEach((visual, k) => {
      try {
        list.push(readVisual(visual, name, namedColors));
      } catch (err) {
        problems.push(`link "${name}", visual ${k + 1}: ${err.message}`);
      }
    });
    if (list.length) visuals.set(name, list);
  }

  const joints = new Map();
  for (const e of robot.children) {
    if (e.nodeName !== 'joint') continue;
    const child = childElement(e, 'child')?.getAttribute('link');
    const parent = childElement(e, 'parent')?.getAttribute('link');
    if (!child || !parent) continue;
    try {
      const { xyz, rpy } = readOrigin(childElement(e, 'origin'));
      const axis = numbers(childElement(e, 'axis')?.getAttribute('xyz') ?? '1 0 0', 3, 'axis xyz');
      joints.set(child, { name: e.getAttribute('name'), type: e.getAttribute('type'), parent, xyz, rpy, axis });
    } catch (err) {
      problems.push(`joint "${e.getAttribute('name')}": ${err.message}`);
    }
  }
  return { visuals, joints, problems };
}

function readVisual(visual, link, namedColors) {
  const { xyz, rpy } = readOrigin(childElement(visual, 'origin'));
  const shape = childElement(visual, 'geometry')?.firstElementChild;
  if (!shape) throw new Error('no <geometry>');
  const geometry = readGeometry(shape);
  const material = childElement(visual, 'material');
  let color = null;
  if (material) {
    color = readColor(material) ?? namedColors.get(material.getAttribute('name')) ?? null;
  }
  return { link, xyz, rpy, geometry, color };
}

function readGeometry(shape) {
  const positive = (name) => {
    const v = Number(shape.getAttribute(name));
    if (!(v > 0) || !Number.isFinite(v)) {
      throw new Error(`${shape.nodeName} ${name} "${shape.getAttribute(name)}" is not a positive number`);
    }
    return v;
  };
  switch (shape.nodeName) {
    case 'box': {
      const size = numbers(shape.getAttribute('size'), 3, 'box size');
      if (size.some((s) => s <= 0)) throw new Error(`box size "${shape.getAttribute('size')}" has a side that is not positive`);
      return { type: 'box', size };
    }
    case 'cylinder':
      return { type: 'cylinder', radius: positive('radius'), length: positive('length') };
    case 'sphere':
      return { type: 'sphere', radius: positive('radius') };
    case 'mesh': {
      const filename = shape.getAttribute('filename');
      if (!filename) throw new Error('mesh without a filename');
      const scale = shape.hasAttribute('scale') ? numbers(shape.getAttribute('scale'), 3, 'mesh scale') : [1, 1, 1];
      return { type: 'mesh', filename, scale };
    }
    default:
      throw new Error(`geometry <${shape.nodeName}> is not box, cylinder, sphere or mesh`);
  }
}

function readOrigin(origin) {
  return {
    xyz: numbers(origin?.getAttribute('xyz') ?? '0 0 0', 3, 'origin xyz'),
    rpy: numbers(origin?.getAttribute('rpy') ?? '0 0 0', 3, 'origin rpy'),
  };
}

// <color rgba="r g b a"/> inside a <material>, components in [0, 1]; null without one.
function readColor(material) {
  const rgba = childElement(material, 'color')?.getAttribute('rgba');
  if (!rgba) return null;
  const c = numbers(rgba, 4, 'material color rgba');
  return c.map((v) => Math.min(Math.max(v, 0), 1));
}

function numbers(text, count, what) {
  const values = String(text).trim().split(/\s+/).map(Number);
  if (values.length !== count || values.some((v) => !Number.isFinite(v))) {
    throw new Error(`${what} "${text}" is not ${count} numbers`);
  }
  return values;
}

function childElement(e, name) {
  return [...e.children].find((c) => c.nodeName === name) ?? null;
}
