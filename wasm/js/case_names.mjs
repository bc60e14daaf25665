// The case's inputs by name, as tools/case_json.cpp reads them and with its messages: q,
// qd, ff_torques as an object keyed by joint name (joints not named: 0), f_ext and
// f_virtual as an object keyed by link name (links not named: no wrench), qdd_given by
// joint name or in model order with null for a joint whose torque is given, the driver
// weights w_fext and w_ff, and the constraint blocks {link, alpha, beta, point, w_fext,
// w_ff} packed for achd_solver_set_blocks. `robot` supplies the
// names: root, tip (null for a tree), jointNames, linkNames (after the root),
// lockedJoints.
import { achdCheckObject, achdFiniteNumber, achdIsArrayLike, achdIsPlainObject, achdReadArray, achdReadNumbers, achdUnlikeJson } from './validation.mjs';

const ACHD_BLOCK_KEYS = ['link', 'alpha', 'beta', 'point', 'w_fext', 'w_ff'];

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

// q (positions = true), qd, ff_torques: an array of numbers in model order, or an object
// by joint name (a floating base's free joint: an array of 7 in q, 6 in the others; not
// named: the identity pose at the origin, at rest); read once (validation.mjs) into a
// Float64Array of the model's length, checked.
export function achdJointValues(value, field, robot, positions = false) {
  const n = positions ? robot.numPositions : robot.numJoints;
  if (!achdIsPlainObject(value)) {
    if (!achdIsArrayLike(value))
      throw new Error(`${field} must be an array of ${n} numbers or an object {joint name: value}${achdUnlikeJson(value)}`);
    return achdReadNumbers(value, field, n);
  }
  const given = achdCheckObject(value, field, null);
  const out = new Float64Array(n);
  if (positions && robot.floating) out[6] = 1;  // qw: the identity orientation
  // (no destructuring in for-of: Emscripten's JS optimizer drops it)
  for (const name of Object.keys(given)) {
    const slot = achdJointSlot(robot, name, positions);
    if (!slot) throw new Error(`${field}: ${achdNoJoint(robot, name)}`);
    if (slot.count === 1) out[slot.start] = achdFiniteNumber(given[name], `${field}['${name}']`);
    else out.set(achdReadNumbers(given[name], `${field}['${name}'] (the floating base)`, slot.count), slot.start);
  }
  return out;
}

// f_ext, f_virtual (`field`): a list of one wrench per link after the root, or an object
// by link name (links not named: no wrench); read once into 6 numbers per link, flat.
export function achdLinkWrenches(value, robot, field = 'f_ext') {
  const nl = robot.linkNames.length, out = new Float64Array(6 * nl);
  if (!achdIsPlainObject(value)) {
    const list = achdReadArray(value, field, 'an array of 6-element wrenches or an object {link name: wrench}', (length) => {
      if (length !== nl) throw new Error(`${field}: expected ${nl} wrenches (one per link after the root), got ${length}`);
    });
    list.forEach((w, l) => out.set(achdReadNumbers(w, `${field}[${l}]`, 6), 6 * l));
    return out;
  }
  const given = achdCheckObject(value, field, null);
  for (const name of Object.keys(given)) {
    const l = robot.linkNames.indexOf(name);
    if (l < 0) throw new Error(`${field}: ${achdNoLink(robot, name)}`);
    out.set(achdReadNumbers(given[name], `${field}['${name}']`, 6), 6 * l);
  }
  return out;
}

// qdd_given: the prescribed joints' accelerations, an object {joint name: qdd} or an array
// in model order with null where the joint's torque is given -> {mask, values} (one per
// joint; values 0 where not prescribed).
export function achdPrescribedJoints(value, robot) {
  const nj = robot.numJoints;
  const mask = new Array(nj).fill(false), values = new Float64Array(nj);
  if (achdIsPlainObject(value)) {
    const given = achdCheckObject(value, 'qdd_given', null);
    for (const name of Object.keys(given)) {
      const slot = achdJointSlot(robot, name, false);
      if (!slot) throw new Error(`qdd_given: ${achdNoJoint(robot, name)}`);
      if (slot.count === 1) values[slot.start] = achdFiniteNumber(given[name], `qdd_given['${name}']`);
      else  // the free joint: [dv/dt; dw/dt], all six prescribed
        values.set(achdReadNumbers(given[name], `qdd_given['${name}'] (the floating base)`, slot.count), slot.start);
      mask.fill(true, slot.start, slot.start + slot.count);
    }
    return { mask, values };
  }
  const list = achdReadArray(value, 'qdd_given',
    `an object {joint name: acceleration} or an array of ${nj} numbers or nulls (null: the joint is not prescribed)`, (length) => {
      if (length !== nj) throw new Error(`qdd_given: expected ${nj} values (one per joint, null where not prescribed), got ${length}`);
    });
  for (let i = 0; i < nj; ++i) {
    if (list[i] === null) continue;
    values[i] = achdFiniteNumber(list[i], `qdd_given[${i}] (joint '${achdJointAtRate(robot, i)}')`);
    mask[i] = true;
  }
  return { mask, values };
}

// w_fext, w_ff of the tip (prefix '') or of a block ('constraints[b].'): one weight per
// alpha column, absent: 1 (the range [0, 1] is checked by the C++ validate, whose
// message the CLI gives too).
export function achdDriverWeights(value, field, nc) {
  if (value === undefined) return new Float64Array(nc).fill(1);
  return achdReadNumbers(value, field, nc, `${nc} values (one per alpha column)`, 'an array of numbers in [0, 1], one per alpha column');
}

// Columns alpha (up to `max` 6-vectors) and beta (one per column, absent: zeros) of a
// block, read once; `prefix` "constraints[b]." names them. alpha: the columns, flat.
export function achdColumns(alphaValue, betaValue, prefix, max) {
  const columns = achdReadArray(alphaValue, `${prefix}alpha`, 'an array of 6-element columns', (length) => {
    if (length > max) throw new Error(`${prefix}alpha: at most ${max} constraints, got ${length}`);
  });
  const k = columns.length, alpha = new Float64Array(6 * k);
  columns.forEach((col, j) => alpha.set(achdReadNumbers(col, `${prefix}alpha[${j}]`, 6), 6 * j));
  const beta = betaValue === undefined ? new Float64Array(k)
    : achdReadNumbers(betaValue, `${prefix}beta`, k, `${k} values (one per alpha column)`, 'an array of numbers');
  return { count: k, alpha, beta };
}

// "constraints": the blocks read once, checked and packed as achd_solver_set_blocks reads
// them: per block [link index, columns k, point (3), alpha (6 k), beta (k), w_fext (k),
// w_ff (k)]. `max`: columns per block. Returns {packed, count (blocks), columns (all
// blocks')}.
export function achdPackBlocks(blocks, robot, max) {
  const list = achdReadArray(blocks, 'constraints', 'an array of blocks {link, alpha, beta, point}');
  const packed = [];
  let columns = 0;
  const owners = [];  // per column: 'link NAME' (nu_owners with coupled joints)
  list.forEach((value, b) => {
    const where = `constraints[${b}]`;
    if (!achdIsPlainObject(value)) throw new Error(`${where} must be an object {link, alpha, beta, point}${achdUnlikeJson(value)}`);
    const block = achdCheckObject(value, where, ACHD_BLOCK_KEYS);
    if (!('link' in block)) throw new Error(`${where}: missing required field 'link'`);
    if (!('alpha' in block)) throw new Error(`${where}: missing required field 'alpha'`);
    if (typeof block.link !== 'string') throw new Error(`${where}.link must be a link name${achdUnlikeJson(block.link)}`);
    const link = robot.linkNames.indexOf(block.link);
    if (link < 0) throw new Error(`${where}.link: ${achdNoLink(robot, block.link)}`);
    const c = achdColumns(block.alpha, block.beta, `${where}.`, max);
    const w_fext = achdDriverWeights(block.w_fext, `${where}.w_fext`, c.count);
    const w_ff = achdDriverWeights(block.w_ff, `${where}.w_ff`, c.count);
    const point = block.point === undefined ? [0, 0, 0] : achdReadNumbers(block.point, `${where}.point`, 3);
    packed.push(link, c.count, ...point, ...c.alpha, ...c.beta, ...w_fext, ...w_ff);
    columns += c.count;
    for (let k = 0; k < c.count; ++k) owners.push(`link ${block.link}`);
  });
  return { packed, count: list.length, columns, owners };
}
