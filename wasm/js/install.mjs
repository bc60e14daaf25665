// What the module object offers (loadURDF, memoryBytes, Effects, constants),
// installed by glue.js on the Emscripten module.
import { achdConstants, achdEffectBitsByKey } from './constants.mjs';
import { achdLastError, achdWasm } from './runtime.mjs';
import { achdCheckObject, achdChoice } from './validation.mjs';
import { achdWithString } from './memory.mjs';
import { Robot } from './robot.mjs';

export function installAchd(Module) {
  // Loads the chain root -> tip from URDF text; throws an Error naming the problem.
  // options.mimic: 'error' (default: a <mimic> joint on the chain is an error) or
  // 'independent' (loaded as a joint of its own, as KDL does); achd::MimicJoints' order.
  Module['loadURDF'] = function loadURDF(text, options) {
    if (typeof text !== 'string') throw new Error('loadURDF: the URDF must be a string');
    achdCheckObject(options, 'loadURDF options', ['root', 'tip', 'mimic']);
    for (const key of ['root', 'tip'])
      if (typeof options[key] !== 'string') throw new Error(`loadURDF: options.${key} must be a link name`);
    const mimic = achdChoice(options.mimic, ['error', 'independent'], 'error', 'loadURDF: options.mimic');
    const ptr = achdWithString(text, (x) => achdWithString(options.root, (r) =>
      achdWithString(options.tip, (t) => achdWasm.module._achd_robot_load(x, r, t, mimic))));
    if (!ptr) throw achdLastError();
    return new Robot(ptr);
  };
  // Bytes of wasm memory (grows, never shrinks): for leak checks.
  Module['memoryBytes'] = function memoryBytes() { return achdWasm.module.HEAPU8.length; };
  // achd.Effects: the effect bits by JS name; achd.constants: everything achd_constants()
  // describes (both frozen, from C++).
  Object.defineProperty(Module, 'Effects', { enumerable: true, get: achdEffectBitsByKey });
  Object.defineProperty(Module, 'constants', { enumerable: true, get: () => achdConstants() });
}
