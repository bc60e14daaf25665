// One source of truth at the C++/JS boundary: the effect bits, enum values, defaults and
// buffer indices the JS wrapper uses are C++'s. Each check reads what C++ actually got
// (achd_solver_options, achd_sim_options, the raw buffer pointers) and compares it with
// achd.constants (achd_constants(): options.hpp, simulator.hpp, achd/names.hpp,
// wasm/src/boundary.hpp), so a value hard-coded in wasm/js that disagrees fails here.
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { join } from 'node:path';
import { before, test } from 'node:test';

import { loadAchd, repo, robots } from './helpers.mjs';

let achd, kuka, entry;
before(async () => {
  achd = await loadAchd();
  entry = robots().find((r) => r.name === 'kuka_lwr4');
  kuka = achd.loadURDF(entry.text, { root: entry.root, tip: entry.tip });
});

// The NUL-terminated UTF-8 string at byte address ptr in wasm memory.
function cString(ptr) {
  const bytes = achd.HEAPU8;
  let end = ptr;
  while (bytes[end] !== 0) ++end;
  return new TextDecoder().decode(bytes.subarray(ptr, end));
}
const solverOptions = (solver) => JSON.parse(cString(achd._achd_solver_options(solver._ptr)));
const simOptions = (sim) => JSON.parse(cString(achd._achd_sim_options(sim._ptr)));
const doubles = (ptr, n) => Array.from(achd.HEAPF64.subarray(ptr >> 3, (ptr >> 3) + n));
const camelCase = (name) => name.replace(/_([a-z])/g, (_, ch) => ch.toUpperCase());

test('achd.constants is the C++ declarations (effect bits, enum names, defaults)', () => {
  const c = achd.constants;
  // Spot values a reader can check against options.hpp, simulator.hpp and case.hpp.
  assert.deepEqual(c.effects, { gravity: 1, velocity_products: 2, external_wrenches: 4, damping: 8,
    friction: 16, rotor_inertia: 32, constraints: 64 });
  assert.equal(c.default_effects, 1 | 2 | 4 | 32 | 64);
  assert.equal(c.all_effects, 127);
  assert.equal(c.max_constraints, 6);
  assert.deepEqual(c.integrators, ['explicit_euler', 'semi_implicit_euler', 'rk4', 'dormand_prince', 'implicit_euler']);
  assert.deepEqual(c.options, { convention: 'physical', effects: c.default_effects, policy: 'truncate',
    tolerance: 1e-12, absolute_tolerance: false, damping: 1e-6, singular_region: 5e-3, max_damping: 2e-2,
    friction_velocity: 0.05 });
  assert.equal(c.simulator_options.solver.policy, 'variable_damping');  // a plain solve keeps 'truncate'
  assert.deepEqual(c.direction_event_kinds, ['limited', 'released', 'resumed']);
  assert.deepEqual(c.case_gravity, [0, 0, -9.81]);
  assert.deepEqual(c.simulator_options.gravity, [0, 0, -9.81]);
  assert.ok(Object.isFrozen(c) && Object.isFrozen(c.options), 'constants are read-only');
  // achd.Effects: the same bits under the camelCase names.
  assert.deepEqual(achd.Effects, Object.fromEntries(Object.entries(c.effects).map(([k, b]) => [camelCase(k), b])));
});

test('a solver created without options holds achd::Options{} and the C++ Case gravity', () => {
  const solver = kuka.createSolver();
  assert.deepEqual(solverOptions(solver), achd.constants.options);
  assert.equal(solver.maxConstraints, achd.constants.max_constraints);
  assert.deepEqual(Array.from(solver.gravity), achd.constants.case_gravity);
  solver.setOptions({});
  assert.deepEqual(solverOptions(solver), achd.constants.options);
  solver.delete();
});

test('a simulator created without options holds achd::SimulatorOptions{}', () => {
  const sim = kuka.createSimulator();
  assert.deepEqual(simOptions(sim), achd.constants.simulator_options);
  sim.delete();
});

test('every enum name reaches C++ as the enum of that name', () => {
  const c = achd.constants;
  for (const integrator of c.integrators) {
    const sim = kuka.createSimulator({ integrator });
    assert.equal(simOptions(sim).integrator, integrator);
    sim.delete();
  }
  for (const limits of c.limit_policies) {
    const sim = kuka.createSimulator({ limits });
    assert.equal(simOptions(sim).limits, limits);
    sim.delete();
  }
  const solver = kuka.createSolver();
  for (const convention of c.conventions)
    for (const policy of c.singularity_policies) {
      solver.setOptions({ convention, policy });
      assert.deepEqual([solverOptions(solver).convention, solverOptions(solver).policy], [convention, policy]);
    }
  solver.delete();
  const sim = kuka.createSimulator();
  sim.reset(entry.q0);
  c.directions.forEach((direction, k) => {
    for (const [mode, name] of [['hold', 'hold'], [0.5, 'accelerate'], ['free', 'free']]) {
      sim.setDirection(direction, mode);
      assert.equal(c.direction_modes[achd._achd_sim_direction_mode(sim._ptr, -1, k)], name, `${direction} ${mode}`);
    }
  });
  sim.delete();
});

test('every effect name sets its C++ bit, in solver, simulator and RNEA options', () => {
  const c = achd.constants;
  const solver = kuka.createSolver();
  for (const [name, bit] of Object.entries(c.effects)) {
    const key = camelCase(name);
    solver.setOptions({ effects: { [key]: false } });
    assert.equal(solverOptions(solver).effects, c.options.effects & ~bit, `${key}: false`);
    solver.setOptions({ effects: { [key]: true } });
    assert.equal(solverOptions(solver).effects, c.options.effects | bit, `${key}: true`);
    const sim = kuka.createSimulator({ effects: { [key]: false } });
    assert.equal(simOptions(sim).effects, c.simulator_options.effects & ~bit, `simulator ${key}: false`);
    sim.delete();
  }
  solver.delete();
  // RNEA's defaults are the solver's: same torques as with every default spelled out.
  const q = entry.q0, qd = q.map((x, i) => 0.1 * i), qdd = q.map((x, i) => -0.2 * i);
  assert.deepEqual(kuka.rnea(q, qd, qdd), kuka.rnea(q, qd, qdd, { effects: c.options.effects,
    gravity: c.case_gravity, frictionVelocity: c.options.friction_velocity }));
});

test('every view and result covers the C++ buffer of its name', () => {
  const c = achd.constants;
  const solver = kuka.createSolver();
  solver.q.set(entry.q0);
  solver.qd.set(entry.q0.map((x, i) => 0.1 * i));
  solver.numConstraints = 2;
  solver.alpha.set([1, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0]);
  solver.beta.set([0.3, -0.2]);
  solver.useExternalWrenches = true;
  solver.useVirtualWrenches = true;
  solver.setPrescribed(['lwr_joint_2']);
  solver.solve();
  const views = ['q', 'qd', 'ff_torques', 'gravity', 'alpha', 'beta', 'f_ext', 'qdd', 'nu', 'joint_torques',
    'constraint_torques', 'total_torques', 'link_accelerations', 'constraint_wrench', 'constraint_wrenches',
    'qdd_given', 'w_fext', 'w_ff', 'f_virtual', 'prescribed_torques', 'virtual_torques', 'coupling_forces'];
  assert.deepEqual(c.solver_buffers.filter((name) => name !== 'dropped'), views, 'a view per C++ buffer');
  for (const name of views)
    assert.equal(solver[name].byteOffset, achd._achd_solver_buffer(solver._ptr, c.solver_buffers.indexOf(name)), name);
  const result = solver.result();
  for (const name of ['qdd', 'nu', 'joint_torques', 'constraint_torques', 'total_torques', 'constraint_wrench',
    'link_accelerations', 'virtual_torques']) {
    const flat = result[name].flat();
    assert.deepEqual(flat, doubles(achd._achd_solver_buffer(solver._ptr, c.solver_buffers.indexOf(name)), flat.length), name);
  }
  solver.delete();

  const sim = kuka.createSimulator();
  sim.reset(entry.q0);
  sim.setDirection('z', 'hold');
  sim.step(3);
  for (const name of ['q', 'qd', 'ff_torques', 'f_ext'])
    assert.equal(sim[name].byteOffset, achd._achd_sim_buffer(sim._ptr, c.simulator_buffers.indexOf(name)), name);
  assert.deepEqual([sim.t], doubles(achd._achd_sim_buffer(sim._ptr, c.simulator_buffers.indexOf('t')), 1));
  for (const name of c.simulator_results) {
    const values = sim[name]();
    assert.ok(values.length > 0, name);
    assert.deepEqual(values, doubles(achd._achd_sim_result(sim._ptr, c.simulator_results.indexOf(name)), values.length), name);
  }
  sim.delete();
});

// The hand-written wasm/achd.d.ts against the module: its name unions and the fields of
// its Constants interfaces are C++'s (tsc checks the rest, tests/node/types.test.mjs).
test('achd.d.ts declares the C++ names and the fields of achd.constants', () => {
  const dts = readFileSync(join(repo, 'wasm/achd.d.ts'), 'utf8');
  const union = (name) => {
    const m = dts.match(new RegExp(`export type ${name} = ([^;]+);`));
    assert.ok(m, `type ${name} in achd.d.ts`);
    return [...m[1].matchAll(/'([^']+)'/g)].map((x) => x[1]).sort();
  };
  const fields = (name) => {
    const m = dts.match(new RegExp(`export interface ${name} \\{\\n([\\s\\S]*?)\\n\\}`));
    assert.ok(m, `interface ${name} in achd.d.ts`);
    return [...m[1].matchAll(/^ {2}readonly (\w+)/gm)].map((x) => x[1]).sort();
  };
  const c = achd.constants;
  const sorted = (list) => [...list].sort();
  assert.deepEqual(union('EffectName'), sorted(Object.keys(c.effects)));
  assert.deepEqual(union('Integrator'), sorted(c.integrators));
  assert.deepEqual(union('LimitPolicy'), sorted(c.limit_policies));
  assert.deepEqual(union('Convention'), sorted(c.conventions));
  assert.deepEqual(union('SingularityPolicy'), sorted(c.singularity_policies));
  assert.deepEqual(union('Direction'), sorted(c.directions));
  assert.deepEqual(union('DirectionEventKind'), sorted(c.direction_event_kinds));
  assert.deepEqual(union('MotionKind'), sorted(c.motion_kinds));
  assert.deepEqual(fields('Constants'), sorted(Object.keys(c)));
  assert.deepEqual(fields('CppOptions'), sorted(Object.keys(c.options)));
  assert.deepEqual(fields('CppSimulatorOptions'), sorted(Object.keys(c.simulator_options)));
  // The Effects interface: the effect names in camelCase.
  const effects = dts.match(/export interface Effects \{\n([\s\S]*?)\n\}/)[1];
  assert.deepEqual([...effects.matchAll(/^ {2}(\w+)\?: boolean;/gm)].map((x) => x[1]).sort(),
    sorted(Object.keys(achd.Effects)));
});
