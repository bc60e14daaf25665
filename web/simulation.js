// One robot stepping on the page: the achd robot and simulator built from the page's
// settings, the start pose, the measured time per step and per solve, the simulator's
// direction events, and plain snapshots of the state. Effects, the integrator and the
// policy are fixed when a simulator is created, so changing them builds a new one from
// the current state.
//
// Directions act on links: every link may have its own set (free / hold / accelerate per
// direction, and whether a held one yields to pushes). The page's controls show one link's
// set, the selected link's (settings.directions and settings.yielding are that set); the
// others are kept here (`sets`). A chain starts with its tip selected; a tree from the
// robot list starts with its default links (robots/index.json "constraints") held in x, y,
// z (or the index's "held" directions), the first one selected. A floating base
// (index "floating") stands with those links on the ground (z = 0) under the joint PD
// controller of its "joint_control", toward the start pose (and toward any pose the
// sliders set). An own floating robot stands the same way on its feet: the leaf links
// lowest at the start pose (web/robot_feet.js), under the controller of OWN_CONTROL.
import { DIRECTIONS, GRAVITY, motionInSimulatorTime, simulatorOptions } from './settings.js';
import { lowestLeaves } from './robot_feet.js';
import { startPose } from './start_pose.js';
import { linkParents } from './link_visuals.js';

// An own floating robot's joint PD: gains from a 5 Hz, critically damped response with
// the torques that hold it at rest under gravity on its held feet.
export const OWN_CONTROL = { frequency: 5, dampingRatio: 1, feedforward: 'hold' };
const HELD_BY_DEFAULT = ['x', 'y', 'z'];

// robots/index.json's joint_control (the scene files' words) as setJointControl takes it.
export function jointControlOf(words) {
  if (!words) return null;
  const { damping_ratio: dampingRatio, ...rest } = words;
  return dampingRatio === undefined ? { ...rest } : { ...rest, dampingRatio };
}

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

const freeSet = () => ({ directions: Object.fromEntries(DIRECTIONS.map((d) => [d, 'free'])),
  yielding: Object.fromEntries(DIRECTIONS.map((d) => [d, false])) });

// The rotation matrix (row-major) of a unit quaternion [qx, qy, qz, qw].
function quaternionRows([x, y, z, w]) {
  return [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w),
    2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w),
    2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)];
}

export class Simulation {
  // source: {name, text, root, tip (none: the whole tree), floating, mimic, inertia, srdf
  // (SRDF text), pose (its group_state), q0 (optional: robots/index.json's pose of the
  // joints; without it the SRDF pose, else for a chain a pose inside the limits away from
  // a singularity, web/start_pose.js, for a tree robot.startPose), constraints (a tree's
  // default held links; an own floating robot: its lowest leaf links), held (their held
  // directions, default x, y, z), jointControl (setJointControl's {kp, kd} or {frequency,
  // dampingRatio, feedforward}: the PD controller toward the start pose), loops (the
  // robot's loop joints, loadURDF's loops: robots/index.json's loops file), closed (the
  // loop joints the user closed on the page, after those)}. Throws an Error naming the
  // problem and owns nothing in that case.
  // previous: the Simulation of the same robot this one replaces with other loops (the
  // user closed or opened one): its state (q, qd, the page's time, every link's
  // directions and point, the PD controller's target) goes on here.
  constructor(achd, source, settings, previous = null) {
    this.name = source.name;
    this.source = source;
    const options = { root: source.root, tip: source.tip ?? undefined, floating: Boolean(source.floating) };
    for (const key of ['mimic', 'inertia', 'srdf', 'pose']) if (source[key]) options[key] = source[key];
    const loops = [...(source.loops ?? []), ...(source.closed ?? [])];
    if (loops.length) options.loops = loops;
    this.robot = achd.loadURDF(source.text, options);
    try {
      // The links as the module loaded them (robot.links: parents, joints, masses).
      const names = [this.robot.root, ...this.robot.linkNames];
      const jointAbove = new Map(this.robot.links.map((l) => [l.name, l.joint]));
      this.movable = [Boolean(this.robot.floating),
        ...this.robot.linkNames.map((l) => Boolean(jointAbove.get(l)) && jointAbove.get(l).type !== 'fixed')];
      // parents[i]: the links() index of the link link i hangs from (-1 for the root).
      const index = new Map(names.map((l, i) => [l, i]));
      const parentOf = linkParents(this.robot);
      this.parents = names.map((l) => {
        for (let up = parentOf.get(l); up !== undefined; up = parentOf.get(up)) {
          if (index.has(up)) return index.get(up);
        }
        return -1;
      });
      // The mass that moves: every link the robot carries, and the root itself when it floats.
      this.mass = this.robot.links.filter((l) => l.name !== this.robot.root || this.robot.floating)
        .reduce((sum, l) => sum + l.mass, 0);
      // The SRDF pose the robot starts from (a name of robot.poses), or null.
      this.pose = source.pose || null;
      this.held = source.held ?? HELD_BY_DEFAULT;
      this.place();
      this.control = source.jointControl ?? (this.own ? OWN_CONTROL : null);
      this.settings = settings;
      this.sets = new Map();  // link name -> {directions, yielding}, the selected one's in settings
      this.points = new Map();  // link name -> [x, y, z] in its frame, where its directions act (default: origin)
      this.selected = this.firstSelected();
      this.tOffset = 0;
      this.sim = null;
      this.solver = null;
      if (previous) this.carryOn(previous);
      else this.build(this.q0, null);
    } catch (err) {
      this.delete();
      throw err;
    }
    this.stepWindow = { ms: 0, steps: 0 };
    this.stepMicros = null;
    this.solveMicros = null;
  }

  // The start pose q0 and the default links: the SRDF pose this.pose names, else the
  // source's q0, else (a chain) a pose inside the limits away from a singularity or (a
  // tree) robot.defaultPose; a floating base stands on its default links (an own one: its
  // lowest leaf links at that pose).
  place() {
    const source = this.source;
    const free = this.robot.floating ? 7 : 0;
    const named = this.pose === null ? null : this.robot.poses[this.pose];
    if (this.pose !== null && !named) {
      const names = Object.keys(this.robot.poses);
      throw new Error(`no pose "${this.pose}" (${names.length ? `the SRDF has ${names.join(', ')}` : 'no SRDF poses'})`);
    }
    const joints = named ? named.slice(free)
      : source.q0 ?? (this.robot.tip ? startPose(this.robot).q : this.robot.defaultPose.slice(free));
    const movableJoints = this.robot.numRates - (this.robot.floating ? 6 : 0);
    if (joints.length !== movableJoints) {
      throw new Error(`q0 has ${joints.length} values, the robot ${movableJoints} joints`);
    }
    const base = !this.robot.floating ? null : named ? named.slice(0, 7)
      : source.q0 ? [0, 0, 0, 0, 0, 0, 1] : this.robot.defaultPose.slice(0, 7);
    this.own = this.robot.floating && !source.constraints;
    this.defaultLinks = this.own ? lowestLeaves(this.robot, [...base, ...joints])
      : (source.constraints ?? []).filter((l) => this.robot.linkNames.includes(l));
    this.q0 = this.robot.floating ? this.floatingPose(base, joints) : [...joints];
  }

  // Goes on from `previous` (the same robot with other loops): its links' directions and
  // points, the selected link, the PD controller's target, and a simulator reset to its
  // q and qd at its time.
  carryOn(previous) {
    this.sets = new Map([...previous.sets].map(([link, set]) => [link, structuredClone(set)]));
    this.points = new Map(previous.points);
    this.selected = previous.selected;
    this.controlTarget = previous.controlTarget;
    this.build(Array.from(previous.sim.q), Array.from(previous.sim.qd), previous.t);
  }

  // Where each loop joint's two frames are: [{name, a, b}], a and b the origins of frame
  // a on link_a and frame b on link_b (links: this state's poses, links()), in the base
  // frame (world for a floating base); they coincide while the loop is closed.
  loopEnds(links) {
    const byName = new Map(links.map((l) => [l.name, l]));
    const at = (link, origin) => {
      const { position: p, rotation: R } = byName.get(link);
      const x = origin?.xyz ?? [0, 0, 0];
      return [0, 1, 2].map((i) => p[i] + R[3 * i] * x[0] + R[3 * i + 1] * x[1] + R[3 * i + 2] * x[2]);
    };
    return [...(this.source.loops ?? []), ...(this.source.closed ?? [])].map((loop) => ({
      name: loop.name, a: at(loop.link_a, loop.origin_a), b: at(loop.link_b, loop.origin_b) }));
  }

  // The link whose directions the controls show first: a chain's tip, else the first
  // default link.
  firstSelected() {
    return this.robot.tip ?? this.defaultLinks[0] ?? this.robot.linkNames.at(-1);
  }

  // Starts again from the SRDF pose `name` (null: from the start pose without one), as if
  // the robot had been loaded in it: the start pose, the default links (an own floating
  // robot's feet at that pose, on the ground) with their default directions and the PD
  // controller's target and hold torques are that pose's; prescribed joints are released,
  // the page's time starts at 0. Throws (nothing changed) on a name robot.poses has not.
  choosePose(name) {
    const previous = this.pose;
    this.pose = name;
    try {
      this.place();
    } catch (err) {
      this.pose = previous;
      this.place();
      throw err;
    }
    this.source.pose = name ?? undefined;
    this.settings.prescribed = {};
    this.points.clear();
    this.sets.clear();
    this.selected = this.firstSelected();
    this.defaultDirections();
    this.tOffset = 0;
    this.controlTarget = null;
    this.build(this.q0, null);
    this.tOffset = 0;
  }

  // A floating base's full q for the joints' q: the root at base ([x, y, z, qx, qy, qz,
  // qw]), moved up or down so that the lowest default link stands at z = 0 (the root at
  // z = 0 without default links).
  floatingPose(base, joints) {
    const q = [base[0], base[1], 0, ...base.slice(3, 7), ...joints];
    const fk = this.robot.forwardKinematics(q);
    const feet = fk.filter((l) => this.defaultLinks.includes(l.name)).map((l) => l.position[2]);
    if (feet.length) q[2] = -Math.min(...feet);
    return q;
  }

  // The links with directions: the selected one's set is settings' (read live).
  linkSet(link) {
    if (link === this.selected) return { directions: this.settings.directions, yielding: this.settings.yielding };
    return this.sets.get(link) ?? freeSet();
  }

  // The links that have a set (the selected one's included), in the robot's link order.
  setLinks() {
    return this.robot.linkNames.filter((l) => l === this.selected || this.sets.has(l));
  }

  // Every link that has a direction that is not free, in the robot's link order.
  constrainedLinks() {
    return this.setLinks().filter((l) => DIRECTIONS.some((d) => this.linkSet(l).directions[d] !== 'free'));
  }

  // Shows (in settings) the set of `link` in the controls; the previous link's is kept.
  select(link) {
    if (!this.robot.linkNames.includes(link)) throw new Error(`no link "${link}" to hold (the root cannot be)`);
    if (link === this.selected) return;
    this.sets.set(this.selected, structuredClone(this.linkSet(this.selected)));
    const next = this.sets.get(link) ?? freeSet();
    this.sets.delete(link);
    this.selected = link;
    Object.assign(this.settings.directions, next.directions);
    Object.assign(this.settings.yielding, next.yielding);
  }

  // Where link's directions act, [x, y, z] in its frame; its held directions hold there
  // from now on.
  setPoint(link, point) {
    this.points.set(link, [...point]);
    this.sim.setDirectionPoint(link, point);
  }

  // The world position of a link's directions' point (links: this state's poses, links()).
  pointOf(link, links) {
    const pose = links[1 + this.robot.linkNames.indexOf(link)];
    const p = this.points.get(link) ?? [0, 0, 0];
    const R = pose.rotation;
    return [0, 1, 2].map((i) => pose.position[i] + R[3 * i] * p[0] + R[3 * i + 1] * p[1] + R[3 * i + 2] * p[2]);
  }

  // A new robot's directions: every link free, the default links held in x, y, z (or the
  // source's held directions); the selected link's set is settings'.
  defaultDirections() {
    this.sets.clear();
    for (const link of this.defaultLinks) {
      const set = freeSet();
      for (const d of this.held) set.directions[d] = 'hold';
      if (link === this.selected) {
        Object.assign(this.settings.directions, set.directions);
        Object.assign(this.settings.yielding, set.yielding);
      } else {
        this.sets.set(link, set);
      }
    }
    if (!this.defaultLinks.includes(this.selected)) {
      Object.assign(this.settings.directions, freeSet().directions);
      Object.assign(this.settings.yielding, freeSet().yielding);
    }
  }

  // (Re)creates the simulator for the current settings, starting from q, qd at the
  // page's time t (default: now).
  build(q, qd, t = this.t) {
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

  // Each direction's priority and the directions, link by link, then the prescribed joints
  // (their jumps onto their trajectories keep the held directions where their links are,
  // at rest) and the PD controller.
  applyDrivers() {
    for (const link of this.setLinks()) {
      if (this.points.has(link)) this.sim.setDirectionPoint(link, this.points.get(link));
      for (const name of DIRECTIONS) {
        this.applyYield(name, link);
        this.applyDirection(name, link);
      }
    }
    // after the directions: a joint's jump onto its trajectory respects the held ones
    for (const joint of Object.keys(this.settings.prescribed)) this.applyPrescribed(joint);
    if (this.control) this.sim.setJointControl({ target: this.controlTarget ?? this.q0, ...this.control });
  }

  // settings.prescribed[joint] (page time) given to the simulator (its time starts at
  // tOffset), or the joint released when it has none.
  applyPrescribed(joint) {
    const m = this.settings.prescribed[joint];
    if (m) this.sim.prescribe(joint, motionInSimulatorTime(m, this.tOffset));
    else this.sim.release(joint);
  }

  // A direction that yields to pushes has w_fext = 0: a push moves its link along it.
  applyYield(name, link = this.selected) {
    this.sim.setDirectionWeights(name, { wFext: this.linkSet(link).yielding[name] ? 0 : 1 }, link);
  }

  get t() {
    return this.sim ? this.tOffset + this.sim.t : undefined;
  }

  rebuild() {
    this.build(Array.from(this.sim.q), Array.from(this.sim.qd));
  }

  // Applies a link's direction (default: the selected link's, settings.directions[name]);
  // a held direction holds where its link is now.
  applyDirection(name, link = this.selected) {
    this.sim.setDirection(name, this.linkSet(link).directions[name], link);
  }

  // Puts the robot at rest at q, the page's clock kept; held directions hold at q, and the
  // PD controller (a floating base's) holds q.
  setPose(q) {
    const t = this.t;
    this.sim.reset(q);
    this.tOffset = t;
    this.eventsSeen = 0;
    if (this.control) this.controlTarget = [...q];
    this.applyDrivers();
  }

  get q() {
    return this.sim.q;
  }

  reset() {
    this.tOffset = 0;
    this.controlTarget = null;
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
    // One block per constrained link, as the simulator builds them.
    s.setConstraints(this.constrainedLinks().map((link) => {
      const set = this.linkSet(link);
      const constrained = DIRECTIONS.filter((d) => set.directions[d] !== 'free');
      return { link, alpha: constrained.map(unitRow), beta: constrained.map(() => 0),
        w_fext: constrained.map((d) => (set.yielding[d] ? 0 : 1)) };
    }));
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

  // Every link's pose, root first (forward kinematics lists the links after the root; a
  // floating root is where q puts it).
  links() {
    const q = this.sim.q;
    const root = this.robot.floating
      ? { name: this.robot.root, position: [q[0], q[1], q[2]], rotation: quaternionRows([q[3], q[4], q[5], q[6]]) }
      : { name: this.robot.root, position: [0, 0, 0], rotation: [1, 0, 0, 0, 1, 0, 0, 0, 1] };
    return [root, ...this.robot.forwardKinematics(q)];
  }

  // nu of the last solve split by link: {link: its columns' multipliers, in direction
  // order}; the blocks come in the simulator's order (sim.directionLinks()).
  nuByLink() {
    const nu = this.sim.nu();
    const out = {};
    let k = 0;
    for (const { link, directions } of this.sim.directionLinks()) {
      if (directions) out[link] = nu.slice(k, k + directions);
      k += directions;
    }
    return out;
  }

  // The constraint wrench of each constrained link at its directions' point, for the
  // arrows: [{name, position, wrench}] (links: this state's poses, links()).
  wrenches(links) {
    const wrenches = this.sim.constraintWrenches();
    return Object.entries(wrenches).map(([name, wrench]) => ({ name, wrench, position: this.pointOf(name, links) }));
  }

  snapshot() {
    return {
      robot: this.name,
      t: this.t,
      q: Array.from(this.sim.q),
      qd: Array.from(this.sim.qd),
      link: this.selected,
      directions: { ...this.settings.directions },
      yielding: { ...this.settings.yielding },
      // every link with a direction that is not free: {link: {directions, yielding, residuals}}
      links: Object.fromEntries(this.constrainedLinks().map((l) => [l, { ...structuredClone(this.linkSet(l)),
        point: this.points.get(l) ?? [0, 0, 0], residuals: this.sim.residuals(l) }])),
      prescribed: structuredClone(this.settings.prescribed),
      residuals: this.sim.residuals(this.selected),
      // of the solve at the start of the last step: nu of the selected link in direction
      // order (its constrained directions), joint_torques per joint
      nu: this.nuByLink()[this.selected] ?? [],
      joint_torques: this.sim.joint_torques(),
      // the loop joints (robot.loops), each with picked: whether the user closed it on the page
      loops: this.robot.loops.map((l) => ({ ...l, picked: (this.source.closed ?? []).some((c) => c.name === l.name) })),
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
