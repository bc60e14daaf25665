// Types of achd.mjs: the Popov-Vereshchagin hybrid dynamics solver (ACHD) in WebAssembly.
// Units SI; spatial vectors linear first [x, y, z, rx, ry, rz]; gravity is the physical
// vector. Plain arrays and objects returned are copies; Float64Array properties of
// Solver and Simulator are views on wasm memory (re-created automatically when memory
// grows, so read the property again rather than keeping a view across a loadURDF,
// create* or delete()). Every object owning wasm memory has delete(); afterwards each
// call throws Error('<Kind> has been deleted'), and views cannot outlive it: delete() of
// an object whose views were read detaches every view on the current memory (they become
// zero-length: element writes are dropped, fill and set throw a TypeError), so a kept
// view never writes into memory another object or the allocator uses. Inputs (Vec: an array or typed array; by-name
// inputs and options: plain objects) are read once into a checked copy; a Map, DataView,
// class instance, getter, a number given as a string or null options are named Errors.
// Bad input throws an Error naming the field and index.
// Names: option values are the scene files' words (explicit_euler, velocity_products),
// option keys the same words in camelCase (velocityProducts), result fields snake_case.

export type Vec = ArrayLike<number>;
export type Vector6 = [number, number, number, number, number, number];

/** The effect names of scene files and achd.constants.effects. */
export type EffectName = 'gravity' | 'velocity_products' | 'external_wrenches' | 'damping' | 'friction'
  | 'rotor_inertia' | 'constraints';
export type Convention = 'physical' | 'kdl';
export type SingularityPolicy = 'truncate' | 'damped' | 'variable_damping';
/** What became of a held or accelerated direction (Simulator.events()). */
export type DirectionEventKind = 'limited' | 'released' | 'resumed';
export type Integrator = 'explicit_euler' | 'semi_implicit_euler' | 'rk4' | 'dormand_prince' | 'implicit_euler';
/** @deprecated the previous release's spellings of 'explicit_euler' and 'semi_implicit_euler';
 * still accepted (with a console.warn) until the next release. */
export type DeprecatedIntegrator = 'euler' | 'semi-implicit';
export type LimitPolicy = 'ignore' | 'report' | 'clamp';

/** Effects of a solve (MuJoCo-style bits), keyed by EffectName in camelCase: unset keys keep their defaults. */
export interface Effects {
  gravity?: boolean;
  velocityProducts?: boolean;
  externalWrenches?: boolean;
  /** -damping * qd (URDF <dynamics damping>); off by default in solve(), on in the simulator. */
  damping?: boolean;
  /** smoothed Coulomb friction; off by default in solve(), on in the simulator. */
  friction?: boolean;
  rotorInertia?: boolean;
  constraints?: boolean;
}

export interface SolveOptions {
  /** 'physical' (default): real accelerations; 'kdl': KDL's beta and link accelerations. */
  convention?: Convention;
  /** singular coupling matrix: 'truncate' (pseudo-inverse, default), 'damped', or 'variable_damping'
   * (damping only in the singular region; the simulator's default). */
  policy?: SingularityPolicy;
  /** truncate: singular values below tolerance * sigma_max (or absolute) are dropped. Default 1e-12. */
  tolerance?: number;
  absoluteTolerance?: boolean;
  /** damped policy: lambda = damping * sigma_max; finite and > 0. Default 1e-6. */
  damping?: number;
  /** an Effects object or the raw bit mask (achd.Effects). */
  effects?: Effects | number;
  /** friction = F tanh(qd / frictionVelocity); finite and > 0. Default 0.05. */
  frictionVelocity?: number;
}

/** Per joint: an array in model order (Robot.jointNames), or an object keyed by joint name (joints not named: 0). */
export type JointValues = Vec | Record<string, number>;

/**
 * Constraints on one link (Popov-Vereshchagin on trees): alpha^T a_P = beta, column by column,
 * a_P the link's spatial acceleration at `point` (linear part: of the point), base axes.
 */
export interface ConstraintBlock {
  /** a link after the root (Robot.linkNames). */
  link: string;
  /** unit constraint forces acting at the point, oriented like the base: one 6-vector per column (<= 6). */
  alpha: Vec[];
  /** one per alpha column; default zeros. */
  beta?: Vec;
  /** where the constraint acts, in the link's frame; default its origin. */
  point?: Vec;
  /** a second link: the block then constrains alpha^T (a_P - a_Q) = beta, a_Q this link's
   *  acceleration at point_b (the robot receives -alpha nu at P and +alpha nu at Q). */
  link_b?: string;
  /** where the block acts on link_b, in its frame; default its origin (only with link_b). */
  point_b?: Vec;
  /** driver priorities per alpha column, each in [0, 1] (default 1): see Case.w_fext, Case.w_ff. */
  w_fext?: Vec;
  w_ff?: Vec;
  /** one boolean per alpha column (default all false): true where the column gives way to
   *  the joints' efforts. Under variable_damping, with r the largest |tau_i| / effort_i of
   *  the solve that follows these columns, the solve follows them for r <= 1, drops them
   *  for r >= 2 and blends the two between (Result.effort_ratio, Result.yielded). */
  yields?: boolean[];
}

/** The case (docs/design.md section 5): q and gravity required, the rest default to zero/none. */
export interface Case {
  q: JointValues;
  qd?: JointValues;
  gravity: Vec;
  /** the tip's constraints (a chain): unit constraint forces at the tip link's origin, base orientation: one 6-vector per constraint (<= 6). */
  alpha?: Vec[];
  /** one per alpha column. */
  beta?: Vec;
  /** constraint blocks on any links, after the tip's columns in nu; up to 36 columns in all. */
  constraints?: ConstraintBlock[];
  /** one wrench per link after the root (base orientation, about the link origin), or an object keyed by link name. */
  f_ext?: Vec[] | Record<string, Vec>;
  ff_torques?: JointValues;
  /** driver priorities of the tip's columns, one per alpha column in [0, 1] (default 1 = the
   * column resists the driver fully): below 1 the share 1 - w of f_ext's (w_fext) or
   * ff_torques' (w_ff) own unconstrained effect along the column passes through. */
  w_fext?: Vec;
  w_ff?: Vec;
  /** virtual wrenches a controller wants on links (as f_ext: per link after the root, or by
   * link name), applied by the joints as torques J^T f_virtual (Result.virtual_torques). */
  f_virtual?: Vec[] | Record<string, Vec>;
  /** prescribed joints: their accelerations, by joint name, or in model order with null
   * for a joint whose torque is given (its ff_torques are then ignored). */
  qdd_given?: Record<string, number> | Array<number | null>;
}

/** A joint the loader held fixed (a chain's movable side joint), at `value` (rad or m). */
export interface LockedJoint {
  name: string;
  value: number;
}

/** The result (docs/design.md section 5); plain arrays (copies). */
export interface Result {
  /** the joint names, in the order of qdd (and of the other per-joint arrays). */
  joints: string[];
  /** the link names, in the order of link_accelerations: the root link first. */
  links: string[];
  qdd: number[];
  /** KDL's -S^T E nu (not the torques that produce the motion). */
  constraint_torques: number[];
  /** KDL's D qdd. */
  total_torques: number[];
  nu: number[];
  /** with loop joints (Robot.loops) or coupled joints (Robot.couplings): who owns each entry
   * of nu ('tip', 'link NAME', 'loop NAME', 'coupling JOINT'); the loops' columns follow the
   * blocks', the couplings' forces come last. */
  nu_owners?: string[];
  /** with loop joints: alpha nu of each loop at frame b's origin, what link a exerts. */
  loop_wrenches?: number[][];
  /** ff - J^T alpha nu = RNEA(q, qd, qdd): what a controller must command. */
  joint_torques: number[];
  /** alpha nu: the wrench the tip exerts on the constraint. */
  constraint_wrench: number[];
  /** per constraint block: alpha nu at its point, base axes. */
  constraint_wrenches: number[][];
  /** root link first, then every link after the root; spatial accelerations. */
  link_accelerations: number[][];
  /** rank of the nc x nc coupling matrix K. */
  rank: number;
  /** smallest singular value of K = A M^-1 A^T for the alpha columns as given (0 without
   * constraints); solve() throws if that K is beyond the range of a double. */
  sigma_min: number;
  /** constraint-space directions truncated or damped (columns of nc numbers). */
  dropped: number[][];
  /** only when a block has yields: the largest |tau_i| / effort_i of the solve that follows
   *  the yielding columns, and how far this solve gave them up (0: followed, 1: wholly). */
  effort_ratio?: number;
  yielded?: number;
  /** only with f_virtual: J^T f_virtual per joint (part of the ff torques). */
  virtual_torques?: number[];
  /** only with qdd_given: per joint, the actuator torque a prescribed joint needs while the
   * constraint forces act; null for the joints whose torque was given. */
  prescribed_torques?: Array<number | null>;
  /** only when the robot has locked joints (Robot.lockedJoints). */
  locked_joints?: LockedJoint[];
}

export interface JointLimits {
  /** -Infinity / Infinity for continuous joints. */
  lower: number;
  upper: number;
  /** 0 = not given. */
  velocity: number;
  effort: number;
}

export interface LinkPose {
  name: string;
  /** origin of the link frame in the root frame. */
  position: [number, number, number];
  /** rotation root <- link, 9 numbers, row-major. */
  rotation: number[];
}

export interface SolverOptions extends SolveOptions {
  /** 0..6, default 6: the length of the alpha (6 per column) and beta views. */
  maxConstraints?: number;
}

/** The zero-copy solver. Write the input views, call solve(), read the output views. */
export interface Solver {
  /** joint rates (Robot.numRates); q has Robot.numPositions numbers. */
  readonly numRates: number;
  /** @deprecated the old name of numRates (it counted joint rates, a free joint 6), kept for one release. */
  readonly numJoints: number;
  readonly numPositions: number;
  readonly numLinks: number;
  readonly maxConstraints: number;
  readonly deleted: boolean;
  // inputs (views)
  readonly q: Float64Array;
  readonly qd: Float64Array;
  readonly ff_torques: Float64Array;
  /** 3 numbers, initially achd.constants.case_gravity ([0, 0, -9.81]). */
  readonly gravity: Float64Array;
  /** 6 * maxConstraints, column-major, linear first; the first numConstraints columns are used. */
  readonly alpha: Float64Array;
  /** maxConstraints; the first numConstraints are used. */
  readonly beta: Float64Array;
  /** 6 per link after the root; read by solve() only while useExternalWrenches is true. */
  readonly f_ext: Float64Array;
  /** 0..maxConstraints (default 0). */
  numConstraints: number;
  /** default false. */
  useExternalWrenches: boolean;
  /** maxConstraints each, initially 1: the driver weights of the tip's columns (the first numConstraints are used). */
  readonly w_fext: Float64Array;
  readonly w_ff: Float64Array;
  /** 6 per link after the root; read by solve() only while useVirtualWrenches is true. */
  readonly f_virtual: Float64Array;
  /** default false. */
  useVirtualWrenches: boolean;
  /** one per joint: the accelerations of the joints setPrescribed names (others not read). */
  readonly qdd_given: Float64Array;
  /** the prescribed joints of the solves that follow: joint names, or one boolean per joint; [] for none. */
  setPrescribed(joints: string[] | boolean[]): void;
  /** one boolean per joint (a copy). */
  readonly prescribed: boolean[];
  /** constraint blocks for the solves that follow (copied in; a solve never allocates); [] for none. */
  setConstraints(blocks: ConstraintBlock[]): void;
  /** blocks set by setConstraints. */
  readonly numBlocks: number;
  // outputs of the last solve (views)
  readonly qdd: Float64Array;
  /** numConstraints plus the blocks' columns long: the tip's, then each block's. */
  readonly nu: Float64Array;
  readonly joint_torques: Float64Array;
  readonly constraint_torques: Float64Array;
  readonly total_torques: Float64Array;
  readonly constraint_wrench: Float64Array;
  /** 6 * numBlocks: alpha nu of each constraint block at its point. */
  readonly constraint_wrenches: Float64Array;
  /** 6 * (numLinks + 1): root link first. */
  readonly link_accelerations: Float64Array;
  /** one per joint: a prescribed joint's torque, 0 for the others. */
  readonly prescribed_torques: Float64Array;
  /** one per joint: J^T f_virtual (0 while useVirtualWrenches is false). */
  readonly virtual_torques: Float64Array;
  /** coupled joints' forces (Robot.couplings), one per coupling, after a solve. */
  readonly coupling_forces: Float64Array;
  readonly rank: number;
  /** smallest singular value of K of the last solve, computed when read (not by solve());
   * throws if that K is beyond the range of a double (columns of length ~1e154). */
  readonly sigma_min: number;
  /** blocks' yielding columns (ConstraintBlock.yields): Result.effort_ratio and Result.yielded of the last solve. */
  readonly effort_ratio: number;
  readonly yielded: number;
  setOptions(options?: SolveOptions): void;
  /** hybrid dynamics in place on the views: no allocation, no copy. Throws on NaN input
   * and when the solve overflows (the message names the joint or constraint column). */
  solve(): void;
  /** the outputs of the last solve as a Result (a copy). */
  result(): Result;
  delete(): void;
}

export type Direction = 'x' | 'y' | 'z' | 'rx' | 'ry' | 'rz';

/** Prescribed joint motion in the simulated time t (rad or m; frequency in Hz):
 *  constant: q = position; ramp: q = position + velocity t;
 *  sine: q = position + amplitude sin(2 pi frequency t + phase). Parameters a kind does not read must be absent or 0. */
export type MotionKind = 'constant' | 'ramp' | 'sine';
export interface JointMotion {
  motion: MotionKind;
  position?: number;
  velocity?: number;
  amplitude?: number;
  frequency?: number;
  phase?: number;
}

export interface SimulatorOptions {
  /** default 'dormand_prince' (adaptive: step(n, dt) takes error-controlled substeps). */
  integrator?: Integrator | DeprecatedIntegrator;
  /** defaults: every effect on (damping and friction included). */
  effects?: Effects | number;
  /** default [0, 0, -9.81]. */
  gravity?: Vec;
  /** joint limits: 'report' (default) records hits, 'clamp' stops the joint there, 'ignore'. */
  limits?: LimitPolicy;
  /** Coulomb friction F tanh(qd / v): v in rad/s or m/s, default 0.05, raised per step for stability. */
  frictionVelocity?: number;
  /** Baumgarte frequency of held directions in rad/s, > 0; default 100 (never from dt). */
  stabilisationFrequency?: number;
  /** Baumgarte damping ratio, default 1. */
  stabilisationDamping?: number;
  /** 'dormand_prince' tolerances, > 0: relative (default 1e-9) and absolute (1e-11). */
  rtol?: number;
  atol?: number;
  /** singular coupling matrix: default 'variable_damping' (a plain solve's default is 'truncate'). */
  policy?: SingularityPolicy;
  /** variable_damping: the singular region eps, relative to sigma_max of the coupling matrix
   * scaled by kind (dimensionless); finite and > 0, default 5e-3. */
  singularRegion?: number;
  /** variable_damping: the damping at sigma = 0, relative the same way; finite and > 0, default 2e-2. */
  maxDamping?: number;
  /** the joint PD controller from the start (Simulator.setJointControl; target required here). */
  jointControl?: JointControl;
}

/** The joint PD controller: every solve adds kp (target - q) - kd qd (+ the hold
 * torques with feedforward 'hold') to ff_torques. Gains are kp and kd, or come from
 * frequency and dampingRatio: kp_i = M_ii (2 pi f)^2, kd_i = 2 zeta M_ii (2 pi f) with M
 * the joint-space inertia at the target. */
export interface JointControl {
  /** a pose as q (numPositions numbers); default the simulator's q when it is set. */
  target?: Vec;
  /** one number for every joint (0 on a floating base's free joint) or numRates numbers, >= 0. */
  kp?: number | Vec;
  /** the same; default 0. */
  kd?: number | Vec;
  /** Hz, > 0: the gains from the joint-space inertia (instead of kp and kd). */
  frequency?: number;
  /** with frequency; default 1 (critically damped). */
  dampingRatio?: number;
  /** 'hold': add the torques that keep the robot at rest at the target under gravity
   * with the held directions (recomputed when they change); default 'none'. */
  feedforward?: 'hold' | 'none';
}

/** A link (name or index into linkNames, the links after the root); omitted: a chain's tip. */
export type LinkRef = string | number;

/** A change of a direction's state under variable_damping (the CLI summary's "events"). */
export interface DirectionEvent {
  /** s, of the state whose solve showed the change. */
  t: number;
  /** steps completed at that state. */
  step: number;
  /** the link whose direction it is (absent for a loop joint's direction). */
  link?: string;
  /** the loop joint whose direction (of its loop frame) it is (absent for a link's). */
  loop?: string;
  direction: Direction;
  /** limited: damped (or a push partly given up for the efforts) with an effect; released:
   * damping dominates, or the push is wholly given up: not followed; resumed:
   * followed again for 0.05 s (a released held direction then holds where the tip is). */
  kind: DirectionEventKind;
  /** the coupling matrix's smallest singular value in that solve. */
  sigma_min: number;
  /** |acceleration asked - delivered| along the direction in that solve (m/s^2 or rad/s^2). */
  unmet: number;
  /** max |tau_i| / effort_i the pushed directions would take from the joints in that solve
   * (above 1 a push gives way; 0 without pushes). */
  effort_ratio: number;
}

/** Options of Simulator.step. */
export interface StepOptions {
  /**
   * Called after every `progressInterval` steps and after the last one, with the steps run
   * so far by this call and its n. Returning false stops the run there; step() then
   * returns stepsDone. Any other return value (or none) continues. It may change the
   * simulator's directions, controls and wrenches (the rest of the run uses them) and
   * create or delete other objects; deleting or resetting this simulator stops the run
   * with an Error saying so, and calling its step() again is refused (an Error).
   */
  onProgress?: (stepsDone: number, total: number) => boolean | void;
  /** steps between onProgress calls, an integer >= 1; default 10000 (about 0.1 s of RK4 on the 7-DoF arm). */
  progressInterval?: number;
}

/** Time stepping under the hybrid solver. */
export interface Simulator {
  /** joint rates: qd's length; q has numPositions numbers (7 + joints with a floating base). */
  readonly numRates: number;
  /** @deprecated the old name of numRates (it counted joint rates, a free joint 6), kept for one release. */
  readonly numJoints: number;
  readonly numPositions: number;
  readonly numLinks: number;
  readonly deleted: boolean;
  /** state views, writable. */
  readonly q: Float64Array;
  readonly qd: Float64Array;
  /** joint torques applied every step (view). */
  readonly ff_torques: Float64Array;
  /** 6 per link after the root (view). */
  readonly f_ext: Float64Array;
  /**
   * simulated time, s: t0 + k * dt after k steps of dt, t0 being the time at reset() or
   * when dt last changed (computed, not summed: step(n, dt) from reset() ends at exactly n * dt).
   */
  readonly t: number;
  /** steps completed since createSimulator() or reset(). */
  readonly stepsTaken: number;
  /** Integrator substeps accepted / rejected since createSimulator() or reset(). */
  readonly substeps: number;
  readonly rejectedSubsteps: number;
  /** Of the accepted substeps, those Dormand-Prince took implicitly after detecting stiffness. */
  readonly stiffSubsteps: number;
  /**
   * n steps of dt seconds (defaults 1, 1e-3); n an integer in [0, 2^53 - 1]. Returns the
   * number of steps run: n, or fewer when options.onProgress stopped the run. A step that
   * fails (the solver refuses the state, or it leaves the finite numbers) throws an Error
   * naming the step, the time, the held and accelerated directions and the cause
   * ("step 2184 from t = 2.183 s to 2.184 s (rk4 stage 4 of 4; held: z, rx; accelerated:
   * y = 0.5 m/s^2) failed: ..."); q, qd and t then stay those of the last good step.
   */
  step(n?: number, dt?: number, options?: StepOptions): number;
  /** new state; t = 0, every direction free. qd defaults to zero. */
  reset(q: Vec, qd?: Vec): void;
  /** On `link` (omitted: a chain's tip; each link has its own set): 'hold' keeps the link's
   *  point where it is along the base axis; a number prescribes its classical acceleration;
   *  'free' releases. At most 36 active directions on all links together. */
  setDirection(name: Direction, mode: 'hold' | 'free' | number, link?: LinkRef): void;
  directionMode(name: Direction, link?: LinkRef): 'free' | 'hold' | 'accelerate';
  /** Driver priorities of a direction, each in [0, 1] (default 1): below 1 the direction
   *  yields to external wrenches (wFext) or feed-forward torques (wFf) and is re-anchored
   *  where its point is after every step. */
  setDirectionWeights(name: Direction, weights?: { wFext?: number; wFf?: number }, link?: LinkRef): void;
  /** where the link's directions act, [x, y, z] in its frame (default its origin). */
  setDirectionPoint(link: LinkRef, point: Vec): void;
  /** links with directions, in the order of their blocks in nu, and their active directions. */
  directionLinks(): { link: string; directions: number }[];
  /** each link's constraint wrench alpha nu at its point (base axes; what the link exerts on
   *  its constraint) in the solve at the start of the last step (copies). */
  constraintWrenches(): Record<string, number[]>;
  setJointControl(control: JointControl): void;
  clearJointControl(): void;
  readonly jointControlOn: boolean;
  /** the joint (name or index) follows `motion` from now on: put on it at once, its
   *  acceleration prescribed in every solve, its q and qd set on the trajectory after every
   *  step; never stopped at a limit (limits 'clamp'). reset() releases every joint. */
  prescribe(joint: number | string, motion: JointMotion): void;
  /** the joint is driven by its torques again, from where it is. */
  release(joint: number | string): void;
  /** names of the prescribed joints, root to tip. */
  prescribedJoints(): string[];
  /** per joint: a prescribed joint's torque in the solve at the start of the last step, 0 for the others (a copy). */
  prescribed_torques(): number[];
  /** held-direction residuals of a link (omitted: the tip) in m or rad; null for directions not held. */
  residuals(link?: LinkRef): Record<Direction, number | null>;
  energy(): { kinetic: number; potential: number; total: number };
  /** each loop joint's closure error (m or rad, the largest over its held directions): now,
   * and the largest since reset(). */
  loopDrift(): Record<string, { now: number; max: number }>;
  /** how long (s) each direction of each loop joint (of its loop frame) was released since reset(). */
  loopReleasedSeconds(): Record<string, Record<Direction, number>>;
  /** names of the joints at or past a limit after the last step (a copy; [] under limits 'ignore'). */
  limitHits(): string[];
  /** direction events since createSimulator() or reset(), oldest first (copies). */
  events(): DirectionEvent[];
  /** how long (s) each direction of a link (omitted: the tip) was released since it was set. */
  releasedSeconds(link?: LinkRef): Record<Direction, number>;
  /** events that happened beyond the simulator's capacity (10000) and were not kept. */
  readonly eventsNotKept: number;
  /** of the solve at the start of the last completed step (copies). */
  nu(): number[];
  joint_torques(): number[];
  /** @deprecated the previous release's name of joint_torques(); warns once, removed in the next release. */
  jointTorques(): number[];
  qdd(): number[];
  /** link: index after the root or link name; wrench in base orientation about the link origin. */
  setExternalWrench(link: number | string, wrench: Vec): void;
  delete(): void;
}

export interface JointSlot {
  readonly name: string;
  readonly type: 'revolute' | 'continuous' | 'prismatic' | 'floating';
  readonly rateIndex: number;
  readonly rateCount: number;
  readonly positionIndex: number;
  readonly positionCount: number;
}

/** A pose: position, and rotation as a row-major 3 x 3 matrix. */
export interface Placement {
  readonly position: readonly [number, number, number];
  readonly rotation: readonly number[];
}

export type VisualGeometry =
  | { readonly type: 'box'; readonly size: readonly [number, number, number] }
  | { readonly type: 'cylinder'; readonly radius: number; readonly length: number }
  | { readonly type: 'sphere'; readonly radius: number }
  | { readonly type: 'mesh'; readonly filename: string; readonly scale: readonly [number, number, number] };

/** A URDF <visual>: its origin in its link's frame, its shape, its material's colour
 * (r, g, b, a in [0, 1]; null when the material gives none). */
export interface Visual extends Placement {
  readonly geometry: VisualGeometry;
  readonly color: readonly [number, number, number, number] | null;
}

export interface RobotLink {
  readonly name: string;
  /** where it is drawn: 0 the root, 1 + its index in linkNames; a merged link: its host's. */
  readonly frame: number;
  /** the URDF parent link; null for the root. */
  readonly parent: string | null;
  /** the URDF joint above it (its URDF type); null for the root. */
  readonly joint: { readonly name: string; readonly type: string } | null;
  /** the joint whose body it rides on; null: fixed to the root. */
  readonly body: string | null;
  /** its own <inertial> mass (kg), 0 without one. */
  readonly mass: number;
  /** a merged link's pose in its frame's link (its joints at their locked values or 0); null for the others. */
  readonly offset: Placement | null;
  readonly visuals: readonly Visual[];
}

export interface Robot {
  readonly root: string;
  /** null for a tree (loaded without a tip). */
  readonly tip: string | null;
  /** joints the loader held fixed: LoadOptions.locked, a chain's movable side joints. */
  readonly lockedJoints: LockedJoint[];
  /** coupled joints (URDF <mimic>): joint = multiplier leader + offset in every solve. */
  readonly couplings: Array<{ joint: string; leader: string; multiplier: number; offset: number }>;
  /** loop joints (LoadOptions.loops): the directions of each loop frame held in every solve
   * (after the case's blocks in nu) and those dropped because the tree holds them. */
  readonly loops: LoopInfo[];
  /** what the loader found odd in the URDF but loaded, or repaired (LoadOptions.inertia),
   * one line per finding naming the link; empty for a clean file. */
  readonly warnings: string[];
  /** q with every joint at 0, or the middle of its limits when 0 is outside them (a
   * floating base at the identity pose). */
  readonly defaultPose: number[];
  /** the SRDF's named poses (LoadOptions.srdf's group_states) as q, by name. */
  readonly poses: Record<string, number[]>;
  /** the pose LoadOptions.pose names, else defaultPose. */
  readonly startPose: number[];
  /** loaded with {floating: true}: a free joint between the world and the root link comes
   * first in jointNames, named after the root, with 7 numbers in q ([x, y, z, qx, qy, qz,
   * qw]) and 6 in qd, qdd and the torques ([v; w], world axes). */
  readonly floating: boolean;
  /** joint rates: the length of qd, qdd and the torques (6 + joints with a floating base). */
  readonly numRates: number;
  /** @deprecated the old name of numRates (it counted joint rates, a free joint 6), kept for one release. */
  readonly numJoints: number;
  /** the length of q (7 + joints with a floating base, else numRates). */
  readonly numPositions: number;
  /** links after the root (fixed-joint links included). */
  readonly numLinks: number;
  readonly jointNames: string[];
  readonly jointTypes: Array<'revolute' | 'continuous' | 'prismatic' | 'floating'>;
  readonly limits: JointLimits[];
  readonly damping: number[];
  readonly friction: number[];
  /** links after the root, parents before children (a chain's tip last). */
  readonly linkNames: string[];
  /** each joint's numbers in q (positions) and in qd, qdd and the torques (rates), in
   * jointNames' order: a floating base's free joint 7 and 6 from 0, every other joint one. */
  readonly joints: readonly JointSlot[];
  /** the links the robot carries as its URDF has them: the root, linkNames, then the links
   * merged into a body without being links of the model (a chain's side branches). */
  readonly links: readonly RobotLink[];
  readonly deleted: boolean;
  solve(c: Case, options?: SolveOptions): Result;
  /** q (and qd, qdd below) as in a Case: in model order or by joint name. */
  forwardKinematics(q: JointValues): LinkPose[];
  /** 6 rows (linear first) x numRates: [v; w] of the tip link's origin, base orientation. */
  tipJacobian(q: JointValues): number[][];
  /** M(q), rotor inertia included unless rotorInertia is false. */
  massMatrix(q: JointValues, options?: { rotorInertia?: boolean }): number[][];
  /** joint torques producing qdd at (q, qd) under gravity (default [0, 0, -9.81]) and f_ext. */
  rnea(q: JointValues, qd: JointValues, qdd: JointValues, options?: { gravity?: Vec; f_ext?: Vec[] | Record<string, Vec>; effects?: Effects | number; frictionVelocity?: number }): number[];
  createSolver(options?: SolverOptions): Solver;
  createSimulator(options?: SimulatorOptions): Simulator;
  /** solvers and simulators created from the robot stay valid. */
  delete(): void;
}

export interface LoadOptions {
  /** default: the URDF's root link. */
  root?: string;
  /** the chain root -> tip; absent: the whole tree below root. */
  tip?: string;
  /** positions (rad or m) of movable joints held fixed there (a chain's other side joints:
   * at 0). */
  locked?: Record<string, number>;
  /** a chain's side branches: 'merge' (default: riding on the body they hang from, no mass
   * lost) or 'ignore' (dropped, as KDL's chain does). */
  sideBranches?: 'merge' | 'ignore';
  /** a joint with a <mimic> element: coupled to its leader in every solve ('couple', the
   * default; Robot.couplings, its force last in nu), a joint of its own as KDL loads it
   * ('independent'), or an Error naming it ('error'). */
  mimic?: 'couple' | 'independent' | 'error';
  /** a free joint (6 DoF) between the world and the root link, whose mass then counts;
   * default false (the root link is the fixed base). */
  floating?: boolean;
  /** the links' inertias: 'accept' (default: loaded whenever the dynamics are defined, odd
   * ones listed in Robot.warnings, a joint that moves no mass held at 0 or the middle of
   * its limits, listed), 'strict' (odd ones and joints that move nothing refused) or
   * 'repair' (made physical with the least change, a massless moving link given a floor
   * mass; listed). */
  inertia?: 'accept' | 'strict' | 'repair';
  /** loop joints closing the tree (a loops file's "loops" list): each its links, its frame
   * on each (they coincide while the loop is closed), its type and axis (frame a). */
  loops?: LoopJoint[];
  /** SRDF text: its group_states become Robot.poses (joints it does not name: as in
   * defaultPose; a floating base from its 'root_joint' entry, x y z qx qy qz qw). */
  srdf?: string;
  /** the group_state of srdf that Robot.startPose is. */
  pose?: string;
}

export interface LoopFrame {
  xyz?: [number, number, number];
  /** roll, pitch, yaw (URDF's fixed axes) */
  rpy?: [number, number, number];
}

/** a loop joint: the joint a tree cannot hold, closed by relative constraint columns. */
export interface LoopJoint {
  name: string;
  link_a: string;
  origin_a?: LoopFrame;
  link_b: string;
  origin_b?: LoopFrame;
  type: 'revolute' | 'prismatic' | 'spherical' | 'fixed';
  /** revolute, prismatic: in frame a (default z) */
  axis?: [number, number, number];
  /** the loop frame's directions to hold (its z along the axis); default: the type's, less
   * those the tree already holds. */
  directions?: Direction[];
}

export interface LoopInfo {
  name: string;
  type: LoopJoint['type'];
  link_a: string;
  link_b: string;
  directions: Direction[];
  dropped: Direction[];
}

export interface Achd {
  loadURDF(text: string, options?: LoadOptions): Robot;
  /** bytes of wasm memory (grows, never shrinks). */
  memoryBytes(): number;
  /** the effect bits, for SolveOptions.effects as a number. */
  readonly Effects: Readonly<Record<keyof Effects, number>>;
  /** what the JS API takes from C++, read from the module (frozen). */
  readonly constants: Constants;
}

/** Option structs as C++ holds them: snake_case fields, enum values by name. */
export interface CppOptions {
  readonly convention: Convention;
  readonly effects: number;
  readonly policy: SingularityPolicy;
  readonly tolerance: number;
  readonly absolute_tolerance: boolean;
  readonly damping: number;
  readonly singular_region: number;
  readonly max_damping: number;
  readonly friction_velocity: number;
}
export interface CppSimulatorOptions {
  readonly integrator: Integrator;
  readonly effects: number;
  readonly gravity: readonly [number, number, number];
  readonly limits: LimitPolicy;
  readonly stabilisation_frequency: number;
  readonly stabilisation_damping: number;
  readonly rtol: number;
  readonly atol: number;
  readonly solver: CppOptions;
}

/** The C++ declarations the JS API uses (achd_constants(): options.hpp, simulator.hpp,
 * achd/names.hpp, wasm/src/boundary.hpp); name lists are in enum order. */
export interface Constants {
  /** achd::Effect bits by name. */
  readonly effects: Readonly<Record<EffectName, number>>;
  /** kDefaultEffects: a plain solve and rnea (no damping, no friction). */
  readonly default_effects: number;
  /** kAllEffects: the simulator's default. */
  readonly all_effects: number;
  readonly max_constraints: number;
  /** kMaxConstraintColumns: columns of all constraint blocks together. */
  readonly max_constraint_columns: number;
  readonly integrators: readonly Integrator[];
  /** the integrators that control their own error (take rtol and atol). */
  readonly adaptive_integrators: readonly Integrator[];
  readonly directions: readonly Direction[];
  readonly direction_modes: readonly ('free' | 'hold' | 'accelerate')[];
  readonly limit_policies: readonly LimitPolicy[];
  readonly conventions: readonly Convention[];
  readonly singularity_policies: readonly SingularityPolicy[];
  readonly direction_event_kinds: readonly DirectionEventKind[];
  readonly motion_kinds: readonly MotionKind[];
  /** achd::Case's default gravity: the solver's and rnea's. */
  readonly case_gravity: readonly [number, number, number];
  /** achd::Options{}: the solver's defaults. */
  readonly options: CppOptions;
  /** achd::SimulatorOptions{}: the simulator's defaults. */
  readonly simulator_options: CppSimulatorOptions;
  /** names of the buffers behind the Solver and Simulator views, and the Simulator results, by C ABI index. */
  readonly solver_buffers: readonly string[];
  readonly simulator_buffers: readonly string[];
  readonly simulator_results: readonly string[];
  /** the kinds of case-shaped inputs the module's C++ case parser reads for the other calls, by C ABI index. */
  readonly input_kinds: readonly string[];
}

export default function createAchd(moduleOverrides?: object): Promise<Achd>;
