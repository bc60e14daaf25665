// What the module object offers (loadURDF, memoryBytes, Effects, constants),
// installed by glue.js on the Emscripten module.
import { achdConstants, achdEffectBitsByKey } from './constants.mjs';
import { achdLastError, achdWasm } from './runtime.mjs';
import { achdCheckObject, achdChoice } from './validation.mjs';
import { achdJsonText } from './json_text.mjs';
import { achdWithScratch, achdWithString } from './memory.mjs';
import { Robot } from './robot.mjs';

export function installAchd(Module) {
  // Loads the chain root -> tip from URDF text, or without a tip the whole tree below
  // root (default: the URDF's root link); throws an Error naming the problem.
  // options.mimic: 'couple' (default: a <mimic> joint follows its leader in every solve,
  // robot.couplings), 'independent' (a joint of its own, as KDL loads it) or 'error';
  // achd::MimicJoints' order.
  // options.locked: {joint name: position}: movable joints held fixed (a chain's other side
  // joints: at 0).
  // options.sideBranches: 'merge' (default: what hangs off a chain rides on the body it
  // hangs from) or 'ignore' (dropped, as KDL's chain does); achd::SideBranches' order.
  // options.floating: true for a free joint between the world and the root link (its 7
  // positions [x, y, z, qx, qy, qz, qw] and 6 rates [v; w] come first).
  // options.inertia: 'accept' (default: odd inertias loaded, joints that move no mass
  // held, listed in robot.warnings), 'strict' (refused) or 'repair' (made physical,
  // listed); achd::InertiaPolicy's order.
  // options.loops: loop joints closing the tree, [{name, link_a, origin_a: {xyz, rpy},
  // link_b, origin_b, type, axis, directions}] (as in a loops file; robot.loops).
  // options.srdf: SRDF text whose named poses (group_states) become robot.poses;
  // options.pose: the one of them robot.startPose is (default: robot.defaultPose).
  Module['loadURDF'] = function loadURDF(text, options) {
    if (typeof text !== 'string') throw new Error('loadURDF: the URDF must be a string');
    if (options === undefined) options = {};  // (null is not "no options": a named error)
    options = achdCheckObject(options, 'loadURDF options', ['root', 'tip', 'mimic', 'locked', 'sideBranches', 'floating', 'inertia', 'srdf', 'pose', 'loops']);
    if (options.loops !== undefined && !Array.isArray(options.loops))
      throw new Error('loadURDF: options.loops must be an array of loop joints');
    if (options.srdf !== undefined && typeof options.srdf !== 'string') throw new Error('loadURDF: options.srdf must be SRDF text (a string)');
    if (options.pose !== undefined && (typeof options.pose !== 'string' || options.srdf === undefined))
      throw new Error('loadURDF: options.pose must name a group_state of options.srdf');
    if (options.floating !== undefined && typeof options.floating !== 'boolean')
      throw new Error('loadURDF: options.floating must be true or false');
    for (const key of ['root', 'tip'])
      if (options[key] !== undefined && typeof options[key] !== 'string')
        throw new Error(`loadURDF: options.${key} must be a link name`);
    const mimic = achdChoice(options.mimic, ['error', 'independent', 'couple'], 'couple', 'loadURDF: options.mimic');
    const inertia = achdChoice(options.inertia, ['accept', 'strict', 'repair'], 'accept', 'loadURDF: options.inertia');
    const sides = achdChoice(options.sideBranches, ['merge', 'ignore'], 'merge', 'loadURDF: options.sideBranches');
    const locked = options.locked === undefined ? {} : achdCheckObject(options.locked, 'loadURDF: options.locked', null);
    const names = Object.keys(locked), values = names.map((name) => locked[name]);
    values.forEach((x, k) => {
      if (typeof x !== 'number' || !Number.isFinite(x))
        throw new Error(`loadURDF: options.locked['${names[k]}'] must be a finite number, got ${x}`);
      if (names[k].includes('\n') || names[k] === '') throw new Error(`loadURDF: options.locked: '${names[k]}' is not a joint name`);
    });
    // Emscripten's JS optimizer predates `??`: the empty names spelled out.
    const root = options.root === undefined ? '' : options.root, tip = options.tip === undefined ? '' : options.tip;
    const ptr = achdWithString(text, (x) => achdWithString(root, (r) =>
      achdWithString(tip, (t) => achdWithString(names.map((n) => `${n}\n`).join(''), (ln) =>
        achdWithScratch(values.length, (v) => {
          achdWasm.module.HEAPF64.set(values, v);
          return achdWithString(options.loops === undefined ? '' : achdJsonText(options.loops), (lp) =>
            achdWasm.module._achd_robot_load(x, r, t, mimic, sides, ln, 8 * v, options.floating ? 1 : 0, inertia, lp));
        })))));
    if (!ptr) throw achdLastError();
    const robot = new Robot(ptr);
    try {
      robot._readPoses(options.srdf === undefined ? '' : options.srdf, options.pose);
    } catch (e) {
      robot.delete();
      throw e;
    }
    return robot;
  };
  // Bytes of wasm memory (grows, never shrinks): for leak checks.
  Module['memoryBytes'] = function memoryBytes() { return achdWasm.module.HEAPU8.length; };
  // achd.Effects: the effect bits by JS name; achd.constants: everything achd_constants()
  // describes (both frozen, from C++).
  Object.defineProperty(Module, 'Effects', { enumerable: true, get: achdEffectBitsByKey });
  Object.defineProperty(Module, 'constants', { enumerable: true, get: () => achdConstants() });
}
