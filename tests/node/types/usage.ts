// Type tests of wasm/achd.d.ts: the API used as a user would, checked by tsc --noEmit
// (tests/node/types.test.mjs). Each `@ts-expect-error` line is a misuse the types must
// refuse; tsc fails if such a line compiles, so both directions are tested. Never run.
import createAchd, {
  type Achd, type Constants, type Integrator, type Result, type Robot, type Simulator, type Solver,
} from 'achd';

declare const urdf: string;

export async function usage(): Promise<void> {
  const achd: Achd = await createAchd();
  const robot: Robot = achd.loadURDF(urdf, { root: 'base', tip: 'tool' });
  const q = new Float64Array(robot.numRates);

  // The copying solve: the case in, the result (snake_case fields) out.
  const r: Result = robot.solve({ q, gravity: [0, 0, -9.81], alpha: [[0, 0, 1, 0, 0, 0]], beta: [0] },
    { convention: 'kdl', policy: 'damped', damping: 1e-6, effects: { velocityProducts: false } });
  const torques: number[] = r.joint_torques;
  const sigma: number = r.sigma_min;
  // @ts-expect-error gravity is required
  robot.solve({ q });
  // @ts-expect-error result fields are snake_case
  r.jointTorques;
  // @ts-expect-error effect keys are camelCase
  robot.solve({ q, gravity: [0, 0, -9.81] }, { effects: { velocity_products: false } });
  // @ts-expect-error convention is 'physical' or 'kdl'
  robot.solve({ q, gravity: [0, 0, -9.81] }, { convention: 'KDL' });

  // Whole trees, names in and out, constraint blocks on links, locked joints.
  const tree: Robot = achd.loadURDF(urdf);
  const chain: Robot = achd.loadURDF(urdf, { tip: 'foot', locked: { knee: 0.5 }, sideBranches: 'ignore' });
  const tip: string | null = tree.tip;
  const locked: number = chain.lockedJoints[0].value;
  const feet: Result = tree.solve({ q: { hip: 0.3 }, gravity: [0, 0, -9.81], f_ext: { foot: [0, 0, 1, 0, 0, 0] },
    constraints: [{ link: 'foot', alpha: [[0, 0, 1, 0, 0, 0]], beta: [0], point: [0, 0, -0.02] }] });
  const names: string[] = feet.joints.concat(feet.links);
  const wrench: number[] = feet.constraint_wrenches[0];
  // @ts-expect-error a block names its link
  tree.solve({ q, gravity: [0, 0, -9.81], constraints: [{ alpha: [[0, 0, 1, 0, 0, 0]] }] });
  // @ts-expect-error sideBranches is 'merge' or 'ignore'
  achd.loadURDF(urdf, { sideBranches: 'drop' });

  // The zero-copy solver: views in, views out.
  const solver: Solver = robot.createSolver({ maxConstraints: 2, effects: achd.Effects.gravity });
  solver.q.set(q);
  solver.numConstraints = 1;
  solver.setConstraints([{ link: 'foot', alpha: [[1, 0, 0, 0, 0, 0]] }]);
  const blockWrenches: Float64Array = solver.constraint_wrenches;
  solver.solve();
  const qdd: Float64Array = solver.qdd;
  // The drivers: prescribed joints, driver weights, virtual wrenches.
  const driven: Result = robot.solve({ q, gravity: [0, 0, -9.81], alpha: [[0, 0, 1, 0, 0, 0]], w_fext: [0], w_ff: [1],
    qdd_given: [null, 0.5], f_virtual: { tool: [0, 0, 1, 0, 0, 0] },
    constraints: [{ link: 'foot', alpha: [[1, 0, 0, 0, 0, 0]], w_fext: [0.5] }] });
  const given: Array<number | null> | undefined = driven.prescribed_torques;
  const virtualTorques: number[] | undefined = driven.virtual_torques;
  solver.setPrescribed(['elbow']);
  solver.qdd_given[1] = 0.5;
  solver.w_fext[0] = 0;
  solver.useVirtualWrenches = true;
  const prescribedTorques: Float64Array = solver.prescribed_torques;
  // Columns that give way to the joints' efforts: one boolean per alpha column.
  const pushed: Result = robot.solve({ q, gravity: [0, 0, -9.81],
    constraints: [{ link: 'foot', alpha: [[0, 0, 1, 0, 0, 0]], beta: [50], yields: [true] }] }, { policy: 'variable_damping' });
  const ratio: number | undefined = pushed.effort_ratio;
  const share: number = solver.yielded + solver.effort_ratio;
  // @ts-expect-error yields takes booleans, not column indices
  robot.solve({ q, gravity: [0, 0, -9.81], constraints: [{ link: 'foot', alpha: [[0, 0, 1, 0, 0, 0]], yields: [0] }] });
  // @ts-expect-error qdd_given by name takes numbers (null only in the array form)
  robot.solve({ q, gravity: [0, 0, -9.81], qdd_given: { elbow: null } });
  // @ts-expect-error views are read-only properties (write into them instead)
  solver.qdd = new Float64Array(7);
  // @ts-expect-error maxConstraints is fixed at creation
  solver.maxConstraints = 3;

  // The simulator: scene-file integrator names; the old spellings still type-check.
  const integrators: Integrator[] = ['explicit_euler', 'semi_implicit_euler', 'rk4'];
  const sim: Simulator = robot.createSimulator({ integrator: integrators[1], limits: 'clamp', gravity: [0, 0, -9.81] });
  robot.createSimulator({ integrator: 'semi-implicit' });
  // @ts-expect-error not an integrator
  robot.createSimulator({ integrator: 'verlet' });
  // @ts-expect-error not a limit policy
  robot.createSimulator({ limits: 'stop' });
  sim.reset(q);
  sim.setDirection('z', 'hold');
  sim.setDirection('rx', 0.5);
  // @ts-expect-error not a direction
  sim.setDirection('w', 'hold');
  // @ts-expect-error not a mode
  sim.setDirection('z', 'stick');
  const steps: number = sim.step(100, 1e-3, { onProgress: (done, total) => done < total, progressInterval: 10 });
  const held: number | null = sim.residuals().z;
  sim.setDirection('x', 'hold', 'foot');
  sim.setDirection('z', 0.2, 3);
  sim.setDirectionPoint('foot', [0, 0, -0.02]);
  sim.setDirectionWeights('z', { wFext: 0 }, 'foot');
  const footHeld: number | null = sim.residuals('foot').x;
  const footReleased: number = sim.releasedSeconds('foot').x;
  const loopReleased: Record<string, Record<string, number>> = sim.loopReleasedSeconds();
  const unmet: number[] = sim.events().map((e) => e.unmet);
  const where: (string | undefined)[] = sim.events().map((e) => e.loop ?? e.link);
  const mode: 'free' | 'hold' | 'accelerate' = sim.directionMode('x', 'foot');
  const sets: { link: string; directions: number }[] = sim.directionLinks();
  const wrenches: Record<string, number[]> = sim.constraintWrenches();
  sim.setJointControl({ target: q, kp: 30, kd: [0.5, 0.5] });
  robot.createSimulator({ jointControl: { target: q, kp: 30 } });
  sim.setJointControl({ frequency: 5, dampingRatio: 1, feedforward: 'hold' });
  // @ts-expect-error feedforward is 'hold' or 'none'
  sim.setJointControl({ frequency: 5, feedforward: 'gravity' });
  const pd: boolean = sim.jointControlOn;
  sim.clearJointControl();
  sim.prescribe('shoulder', { motion: 'sine', position: 0, amplitude: 0.3, frequency: 0.5 });
  sim.prescribe(0, { motion: 'ramp', velocity: 0.1 });
  sim.release('shoulder');
  const moving: string[] = sim.prescribedJoints();
  const motorTorques: number[] = sim.prescribed_torques();
  // @ts-expect-error not a motion kind
  sim.prescribe('shoulder', { motion: 'square' });
  const tau: number[] = sim.joint_torques();
  const old: number[] = sim.jointTorques();  // deprecated alias, still typed

  // What the API takes from C++.
  const c: Constants = achd.constants;
  const tolerance: number = c.options.tolerance;
  const gravity: readonly [number, number, number] = c.simulator_options.gravity;
  const integrator: Integrator = c.simulator_options.integrator;
  const bit: number = c.effects.velocity_products;
  // @ts-expect-error constants are read-only
  c.max_constraints = 7;
  // @ts-expect-error effects are named as in scene files here
  c.effects.velocityProducts;

  void [torques, sigma, qdd, steps, held, tau, old, tolerance, gravity, integrator, bit];
  sim.delete();
  solver.delete();
  robot.delete();
}
