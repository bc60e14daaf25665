// One robot stepping on the page: the achd robot and simulator built from the page's
// settings, the start pose, the measured time per step and per solve, the simulator's
// direction events, and plain snapshots of the state. Effects, the integrator and the
// policy are fixed when a simulator is created, so changing them builds a new one from
// the current state.
import { DIRECTIONS, GRAVITY, motionInSimulatorTime, simulatorOptions } from './settings.js';
import { startPose } from './start_pose.js';
import { chainLinks, isMovable, urdfTree } from './urdf_tree.js';

// The time per step shown is the mean over at least this much wall time: one frame's
// worth of steps is below the browser's timer resolution on a fast robot.
const TIMING_WINDOW_MS = 250;
const SOLVE_TIMING_CALLS = 300;
// Spring of the push, per kg of the chain: a 1/3 m drag then weighs about the robot;
// the force is capped at three times the robot's weight.
const PUSH_STIFFNESS_PER_KG = 30;
const PUSH_MAX_WEIGHTS = 3;

function unitRow(name) {
  const row = [0, 0, 0, 0, 0, 0];
  row[DIRECTIONS.indexOf(name)] = 1;
  return row;
}

export class Simulation {
  // source: {name, text, root, tip, q0 (optional: robots/index.json's pose; without it, a
  // pose inside the limits away from a singularity, web/start_pose.js)}. Throws an Error
  // naming the problem and owns nothing in that case.
  constructor(achd, source, settings) {
    this.name = source.name;
    this.source = source;
    this.robot = achd.loadURDF(source.text, { root: source.root, tip: source.tip });
    try {
      const tree = urdfTree(source.text);
      const chain = chainLinks(tree, this.robot.root, this.robot.tip) ?? [];
      this.movable = [false, ...this.robot.linkNames.map((l) => isMovable(tree, l))];
      this.mass = chain.reduce((sum, l) => sum + (tree.mass.get(l) ?? 0), 0);
      this.q0 = source.q0 ?? startPose(this.robot).q;
      if (this.q0.length !== this.robot.numJoints) {
        throw new Error(`q0 has ${this.q0.length} values, the chain ${this.robot.numJoints} joints`);
      }
      this.settings = settings;
      this.tOffset = 0;
      this.sim = null;
      this.solver = null;
      this.build(this.q0, null);
    } catch (err) {
      this.delete();
      throw err;
    }
    this.stepWindow = { ms: 0, steps: 0 };
    this.stepMicros = null;
    this.solveMicros = null;
  }

  // (Re)creates the simulator for the current settings, starting from q, qd.
  build(q, qd) {
    const t = this.t;
    this.sim?.delete();
    this.solver?.delete();
    this.sim = null;
    this.solver = null;
    const options = simulatorOptions(this.settings);
    this.sim = this.robot.createSimulator(options);
    this.sim.reset(q, qd ?? undefined);
    this.tOffset = t ?? 0;
    this.eventsSeen = 0;
    // The solver mirrors the simulator's solve so that its time can be measured alone.
    this.solver = this.robot.createSolver({ effects: options.effects });
    this.solver.useExternalWrenches = this.settings.effects.externalWrenches;
    this.applyDrivers();
  }

  // The prescribed joints first (a held direction then holds where the tip is on their
  // trajectories), each direction's priority, then the directions.
  applyDrivers() {
    for (const joint of Object.keys(this.settings.prescribed)) this.applyPrescribed(joint);
    for (const name of DIRECTIONS) {
      this.applyYield(name);
      this.applyDirection(name);
    }
  }

  // settings.prescribed[joint] (page time) given to the simulator (its time starts at
  // tOffset), or the joint released when it has none.
  applyPrescribed(joint) {
    const m = this.settings.prescribed[joint];
    if (m) this.sim.prescribe(joint, motionInSimulatorTime(m, this.tOffset));
    else this.sim.release(joint);
  }

  // A direction that yields to pushes has w_fext = 0: a push moves the tip along it.
  applyYield(name) {
    this.sim.setDirectionWeights(name, { wFext: this.settings.yielding[name] ? 0 : 1 });
  }

  get t() {
    return this.sim ? this.tOffset + this.sim.t : undefined;
  }

  rebuild() {
    this.build(Array.from(this.sim.q), Array.from(this.sim.qd));
  }

  // Applies settings.directions[name]; a held direction holds where the tip is now.
  applyDirection(name) {
    this.sim.setDirection(name, this.settings.directions[name]);
  }

  // Puts the robot at rest at q, the page's clock kept; held directions hold at q.
  setPose(q) {
    const t = this.t;
    this.sim.reset(q);
    this.tOffset = t;
    this.eventsSeen = 0;
    for (const name of DIRECTIONS) this.applyDirection(name);
  }

  get q() {
    return this.sim.q;
  }

  reset() {
    this.tOffset = 0;
    this.sim.reset(this.q0);
    this.eventsSeen = this.events().length;
    // reset() releases every direction and prescribed joint; the page keeps the user's choices.
    this.applyDrivers();
  }

  // Every direction event of this simulator (since it was built or reset), t on the page's
  // clock.
  events() {
    return this.sim.events().map((e) => ({ ...e, t: this.tOffset + e.t }));
  }

  // The events since the last call.
  newEvents() {
    const all = this.events();
    const fresh = all.slice(this.eventsSeen);
    this.eventsSeen = all.length;
    return fresh;
  }

  step(n) {
    const start = performance.now();
    this.sim.step(n, this.settings.dt);
    const w = this.stepWindow;
    w.ms += performance.now() - start;
    w.steps += n;
    if (w.ms >= TIMING_WINDOW_MS) {
      this.stepMicros = (1000 * w.ms) / w.steps;
      w.ms = 0;
      w.steps = 0;
    }
  }

  // The mean of the last full timing window, or of the steps so far before that.
  currentStepMicros() {
    const w = this.stepWindow;
    return this.stepMicros ?? (w.steps ? (1000 * w.ms) / w.steps : null);
  }

  // Times the solve the simulator does at its current state, alone: one hybrid dynamics
  // call with the held and accelerated directions as constraints, their driver weights and
  // the prescribed joints.
  measureSolve() {
    const s = this.solver;
    s.q.set(this.sim.q);
    s.qd.set(this.sim.qd);
    s.gravity.set(GRAVITY);
    const constrained = DIRECTIONS.filter((d) => this.settings.directions[d] !== 'free');
    s.numConstraints = constrained.length;
    constrained.forEach((d, k) => {
      s.alpha.set(unitRow(d), 6 * k);
      s.beta[k] = 0;
      s.w_fext[k] = this.settings.yielding[d] ? 0 : 1;
    });
    s.setPrescribed(Object.keys(this.settings.prescribed));
    s.qdd_given.fill(0);
    s.f_ext.set(this.sim.f_ext);
    const start = performance.now();
    for (let i = 0; i < SOLVE_TIMING_CALLS; i++) s.solve();
    this.solveMicros = (1000 * (performance.now() - start)) / SOLVE_TIMING_CALLS;
  }

  pushStiffness() {
    return PUSH_STIFFNESS_PER_KG * Math.max(this.mass, 0.1);
  }

  pushMaxForce() {
    return PUSH_MAX_WEIGHTS * 9.81 * Math.max(this.mass, 0.1);
  }

  // fkIndex: index into links() (root = 0); wrench null clears it.
  setPush(fkIndex, wrench) {
    this.sim.setExternalWrench(fkIndex - 1, wrench ?? [0, 0, 0, 0, 0, 0]);
  }

  // Every link's pose, root first (forward kinematics lists the links after the root).
  links() {
    const root = { name: this.robot.root, position: [0, 0, 0], rotation: [1, 0, 0, 0, 1, 0, 0, 0, 1] };
    return [root, ...this.robot.forwardKinematics(this.sim.q)];
  }

  snapshot() {
    return {
      robot: this.name,
      t: this.t,
      q: Array.from(this.sim.q),
      qd: Array.from(this.sim.qd),
      directions: { ...this.settings.directions },
      yielding: { ...this.settings.yielding },
      prescribed: structuredClone(this.settings.prescribed),
      residuals: this.sim.residuals(),
      // of the solve at the start of the last step: nu in direction order (the constrained
      // ones), joint_torques per joint
      nu: this.sim.nu(),
      joint_torques: this.sim.joint_torques(),
      stepMicros: this.currentStepMicros(),
    };
  }

  delete() {
    this.solver?.delete();
    this.sim?.delete();
    if (!this.robot.deleted) this.robot.delete();
    this.solver = null;
    this.sim = null;
  }
}
