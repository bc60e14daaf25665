// The case's inputs by name, as tools/case_json.cpp reads them and with its messages: q,
// qd, ff_torques as an object keyed by joint name (joints not named: 0), f_ext and
// f_virtual as an object keyed by link name (links not named: no wrench), qdd_given by
// joint name or in model order with null for a joint whose torque is given, the driver
// weights w_fext and w_ff, and the constraint blocks {link, alpha, beta, point, w_fext,
// w_ff} packed for achd_solver_set_blocks. `robot` supplies the
// names: root, tip (null for a tree), jointNames, linkNames (after the root),
// lockedJoints.
import { achdCheckVector, achdIsArrayLike } from './validation.mjs';

const ACHD_BLOCK_KEYS = ['link', 'alpha', 'beta', 'point', 'w_fext', 'w_ff'];

function achdIsPlainObject(v) {
  return v !== null && typeof v === 'object' && !achdIsArrayLike(v);
}

function achdNumber(x, where) {
  if (typeof x !== 'number') throw new Error(`${where} must be a number`);
  if (!Number.isFinite(x)) throw new Error(`${where} is not finite`);
  return x;
}

// Why `name` is not a movable joint of the robot.
export function achdNoJoint(robot, name) {
  const locked = robot.lockedJoints.find((j) => j.name === name);
  if (locked) return `joint '${name}' is locked at ${locked.value} (a side joint of the chain; --lock sets its position)`;
  if (robot.tip !== null) return `no movable joint '${name}' between the root and the tip`;
  return `no movable joint '${name}' below the root link '${robot.root}'`;
}

// Where joint `name`'s numbers are in a per-joint array, {start, count}, or null: a
// floating base's free joint (first) has 7 in q (positions) and 6 in the others, every
// other joint one.
export function achdJointSlot(robot, name, positions) {
  const j = robot.jointNames.indexOf(name);
  if (j < 0) return null;
  if (!robot.floating) return { start: j, count: 1 };
  if (j === 0) return { start: 0, count: positions ? 7 : 6 };
  return { start: j + (positions ? 6 : 5), count: 1 };
}

// The joint whose rate is entry i of qd, qdd or the torques.
function achdJointAtRate(robot, i) {
  return robot.jointNames[robot.floating ? Math.max(0, i - 5) : i];
}

// Why `name` names no link after the root.
export function achdNoLink(robot, name) {
  if (name === robot.root && robot.floating)
    return `'${name}' is the floating root link, which does not take wrenches or constraint blocks yet (use a link fixed to it)`;
  if (name === robot.root) return `'${name}' is the root link, which is fixed (nothing acts on the model through it)`;
  return `no link '${name}'${robot.tip !== null ? ' on the chain' : ` below the root link '${robot.root}'`}`;
}

// q (positions = true), qd, ff_torques: an object by joint name becomes the array in model
// order (a floating base's free joint: an array of 7 in q, 6 in the others; not named: the
// identity pose at the origin, at rest); anything else is returned as given
// (achdWriteVector checks it).
export function achdJointValues(value, field, robot, positions = false) {
  const n = positions ? robot.numPositions : robot.numJoints;
  if (!achdIsPlainObject(value)) {
    if (value !== undefined && !achdIsArrayLike(value))
      throw new Error(`${field} must be an array of ${n} numbers or an object {joint name: value}`);
    return value;
  }
  const out = new Array(n).fill(0);
  if (positions && robot.floating) out[6] = 1;  // qw: the identity orientation
  // (no destructuring in for-of: Emscripten's JS optimizer drops it)
  for (const name of Object.keys(value)) {
    const x = value[name];
    const slot = achdJointSlot(robot, name, positions);
    if (!slot) throw new Error(`${field}: ${achdNoJoint(robot, name)}`);
    if (slot.count === 1) {
      out[slot.start] = achdNumber(x, `${field}['${name}']`);
      continue;
    }
    achdCheckVector(x, `${field}['${name}'] (the floating base)`, slot.count);
    for (let k = 0; k < slot.count; ++k) out[slot.start + k] = x[k];
  }
  return out;
}

// f_ext, f_virtual (`field`): an object by link name becomes the list of one wrench per
// link after the root.
export function achdLinkWrenches(value, robot, field = 'f_ext') {
  if (!achdIsPlainObject(value)) {
    if (!Array.isArray(value)) throw new Error(`${field} must be an array of 6-element wrenches or an object {link name: wrench}`);
    return value;
  }
  const out = robot.linkNames.map(() => [0, 0, 0, 0, 0, 0]);
  for (const name of Object.keys(value)) {
    const w = value[name];
    const l = robot.linkNames.indexOf(name);
    if (l < 0) throw new Error(`${field}: ${achdNoLink(robot, name)}`);
    achdCheckVector(w, `${field}['${name}']`, 6);
    out[l] = Array.from(w);
  }
  return out;
}

// qdd_given: the prescribed joints' accelerations, an object {joint name: qdd} or an array
// in model order with null where the joint's torque is given -> {mask, values} (one per
// joint; values 0 where not prescribed).
export function achdPrescribedJoints(value, robot) {
  const nj = robot.numJoints;
  const mask = new Array(nj).fill(false), values = new Array(nj).fill(0);
  if (achdIsPlainObject(value)) {
    for (const name of Object.keys(value)) {
      const slot = achdJointSlot(robot, name, false);
      if (!slot) throw new Error(`qdd_given: ${achdNoJoint(robot, name)}`);
      if (slot.count === 1) {
        values[slot.start] = achdNumber(value[name], `qdd_given['${name}']`);
      } else {  // the free joint: [dv/dt; dw/dt], all six prescribed
        achdCheckVector(value[name], `qdd_given['${name}'] (the floating base)`, slot.count);
        for (let k = 0; k < slot.count; ++k) values[slot.start + k] = value[name][k];
      }
      mask.fill(true, slot.start, slot.start + slot.count);
    }
    return { mask, values };
  }
  if (!achdIsArrayLike(value))
    throw new Error(`qdd_given must be an object {joint name: acceleration} or an array of ${nj} numbers or nulls (null: the joint is not prescribed)`);
  if (value.length !== nj)
    throw new Error(`qdd_given: expected ${nj} values (one per joint, null where not prescribed), got ${value.length}`);
  for (let i = 0; i < nj; ++i) {
    if (value[i] === null) continue;
    values[i] = achdNumber(value[i], `qdd_given[${i}] (joint '${achdJointAtRate(robot, i)}')`);
    mask[i] = true;
  }
  return { mask, values };
}

// w_fext, w_ff of the tip (prefix '') or of a block ('constraints[b].'): one weight per
// alpha column, absent: 1 (the range [0, 1] is checked by the C++ validate, whose
// message the CLI gives too).
export function achdDriverWeights(value, field, nc) {
  if (value === undefined) return new Array(nc).fill(1);
  if (!achdIsArrayLike(value)) throw new Error(`${field} must be an array of numbers in [0, 1], one per alpha column`);
  if (value.length !== nc)
    throw new Error(`${field}: expected ${nc} values (one per alpha column), got ${value.length}`);
  return Array.from(value, (x, k) => achdNumber(x, `${field}[${k}]`));
}

// Columns alpha (up to `max` 6-vectors) and beta (one per column, absent: zeros) of a
// block; `prefix` "constraints[b]." names them.
function achdColumns(block, prefix, max) {
  const alpha = block.alpha;
  if (!Array.isArray(alpha)) throw new Error(`${prefix}alpha must be an array of 6-element columns`);
  if (alpha.length > max) throw new Error(`${prefix}alpha: at most ${max} constraints, got ${alpha.length}`);
  alpha.forEach((col, k) => achdCheckVector(col, `${prefix}alpha[${k}]`, 6));
  const k = alpha.length;
  let beta = new Array(k).fill(0);
  if (block.beta !== undefined) {
    if (!achdIsArrayLike(block.beta)) throw new Error(`${prefix}beta must be an array of numbers`);
    if (block.beta.length !== k)
      throw new Error(`${prefix}beta: expected ${k} values (one per alpha column), got ${block.beta.length}`);
    beta = Array.from(block.beta, (x, j) => achdNumber(x, `${prefix}beta[${j}]`));
  }
  return { alpha: alpha, beta: beta };
}

// "constraints": the blocks checked and packed as achd_solver_set_blocks reads them: per
// block [link index, columns k, point (3), alpha (6 k), beta (k), w_fext (k), w_ff (k)].
// `max`: columns per block.
export function achdPackBlocks(blocks, robot, max) {
  if (!Array.isArray(blocks)) throw new Error('constraints must be an array of blocks {link, alpha, beta, point}');
  const packed = [];
  blocks.forEach((block, b) => {
    const where = `constraints[${b}]`;
    if (!achdIsPlainObject(block)) throw new Error(`${where} must be an object {link, alpha, beta, point}`);
    for (const key of Object.keys(block))
      if (!ACHD_BLOCK_KEYS.includes(key)) throw new Error(`${where}: unknown field '${key}'`);
    if (!('link' in block)) throw new Error(`${where}: missing required field 'link'`);
    if (!('alpha' in block)) throw new Error(`${where}: missing required field 'alpha'`);
    if (typeof block.link !== 'string') throw new Error(`${where}.link must be a link name`);
    const link = robot.linkNames.indexOf(block.link);
    if (link < 0) throw new Error(`${where}.link: ${achdNoLink(robot, block.link)}`);
    const columns = achdColumns(block, `${where}.`, max), alpha = columns.alpha;
    const w_fext = achdDriverWeights(block.w_fext, `${where}.w_fext`, alpha.length);
    const w_ff = achdDriverWeights(block.w_ff, `${where}.w_ff`, alpha.length);
    let point = [0, 0, 0];
    if (block.point !== undefined) {
      achdCheckVector(block.point, `${where}.point`, 3);
      point = Array.from(block.point);
    }
    packed.push(link, alpha.length, ...point);
    for (const col of alpha) packed.push(...Array.from(col));
    packed.push(...columns.beta);
    packed.push(...w_fext, ...w_ff);
  });
  return packed;
}
