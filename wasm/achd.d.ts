// Types of achd.mjs: the Popov-Vereshchagin hybrid dynamics solver (ACHD) in WebAssembly.
// Units SI; spatial vectors linear first [x, y, z, rx, ry, rz]; gravity is the physical
// vector. Plain arrays and objects returned are copies; Float64Array properties of
// Solver and Simulator are views on wasm memory (re-created automatically when memory
// grows, so read the property again rather than keeping a view across a loadURDF/malloc).
// Every object owning wasm memory has delete(); afterwards each call throws
// Error('<Kind> has been deleted'). Bad input throws an Error naming the field and index.

export type Vec = ArrayLike<number>;
export type Vector6 = [number, number, number, number, number, number];

/** Effects of a solve (MuJoCo-style bits): unset keys keep their defaults. */
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
  convention?: 'physical' | 'kdl';
  /** singular coupling matrix: 'truncate' (pseudo-inverse, default) or 'damped'. */
  policy?: 'truncate' | 'damped';
  /** truncate: singular values below tolerance * sigma_max (or absolute) are dropped. Default 1e-12. */
  tolerance?: number;
  absoluteTolerance?: boolean;
  /** damped policy: lambda = damping * sigma_max. Default 1e-6. */
  damping?: number;
  /** an Effects object or the raw bit mask (achd.Effects). */
  effects?: Effects | number;
  /** friction = F tanh(qd / frictionVelocity). Default 0.05. */
  frictionVelocity?: number;
}

/** DESIGN.md's case: q and gravity required; the rest default to zero / none. */
export interface Case {
  q: Vec;
  qd?: Vec;
  gravity: Vec;
  /** unit constraint forces at the tip link's origin, base orientation: one 6-vector per constraint (<= 6). */
  alpha?: Vec[];
  /** one per alpha column. */
  beta?: Vec;
  /** one wrench per link after the root (base orientation, about the link origin). */
  f_ext?: Vec[];
  ff_torques?: Vec;
}

/** DESIGN.md's result; plain arrays (copies). */
export interface Result {
  qdd: number[];
  /** KDL's -S^T E nu (not the torques that produce the motion). */
  constraint_torques: number[];
  /** KDL's D qdd. */
  total_torques: number[];
  nu: number[];
  /** ff - J^T alpha nu = RNEA(q, qd, qdd): what a controller must command. */
  joint_torques: number[];
  /** alpha nu: the wrench the tip exerts on the constraint. */
  constraint_wrench: number[];
  /** root link first, then every link after the root; spatial accelerations. */
  link_accelerations: number[][];
  /** rank of the nc x nc coupling matrix K. */
  rank: number;
  /** smallest singular value of K (0 without constraints). */
  sigma_min: number;
  /** constraint-space directions truncated or damped (columns of nc numbers). */
  dropped: number[][];
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
  readonly numJoints: number;
  readonly numLinks: number;
  readonly maxConstraints: number;
  readonly deleted: boolean;
  // inputs (views)
  readonly q: Float64Array;
  readonly qd: Float64Array;
  readonly ff_torques: Float64Array;
  /** 3 numbers, initially [0, 0, -9.81]. */
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
  // outputs of the last solve (views)
  readonly qdd: Float64Array;
  /** numConstraints long. */
  readonly nu: Float64Array;
  readonly joint_torques: Float64Array;
  readonly constraint_torques: Float64Array;
  readonly total_torques: Float64Array;
  readonly constraint_wrench: Float64Array;
  /** 6 * (numLinks + 1): root link first. */
  readonly link_accelerations: Float64Array;
  readonly rank: number;
  /** smallest singular value of K of the last solve, computed when read (not by solve()). */
  readonly sigma_min: number;
  setOptions(options?: SolveOptions): void;
  /** hybrid dynamics in place on the views: no allocation, no copy. Throws on NaN input. */
  solve(): void;
  /** the outputs of the last solve as a Result (a copy). */
  result(): Result;
  delete(): void;
}

export type Direction = 'x' | 'y' | 'z' | 'rx' | 'ry' | 'rz';

export interface SimulatorOptions {
  integrator?: 'rk4' | 'euler' | 'semi-implicit';
  /** defaults: every effect on (damping and friction included). */
  effects?: Effects | number;
  /** default [0, 0, -9.81]. */
  gravity?: Vec;
  /** joint limits: 'report' (default) records hits, 'clamp' stops the joint there, 'ignore'. */
  limits?: 'report' | 'clamp' | 'ignore';
  /** Coulomb friction F tanh(qd / v): v in rad/s or m/s, default 0.05, raised per step for stability. */
  frictionVelocity?: number;
  /** Baumgarte frequency of held directions in rad/s; default 0 = 0.1 / dt. */
  stabilisationFrequency?: number;
  /** Baumgarte damping ratio, default 1. */
  stabilisationDamping?: number;
}

/** Time stepping under the hybrid solver. */
export interface Simulator {
  readonly numJoints: number;
  readonly numLinks: number;
  readonly deleted: boolean;
  /** state views, writable. */
  readonly q: Float64Array;
  readonly qd: Float64Array;
  /** joint torques applied every step (view). */
  readonly ff_torques: Float64Array;
  /** 6 per link after the root (view). */
  readonly f_ext: Float64Array;
  /** simulated time, s. */
  readonly t: number;
  /** n steps of dt seconds (defaults 1, 1e-3). */
  step(n?: number, dt?: number): void;
  /** new state; t = 0, every direction free. qd defaults to zero. */
  reset(q: Vec, qd?: Vec): void;
  /** 'hold' keeps the tip where it is along the base axis; a number prescribes the classical tip acceleration; 'free' releases. */
  setDirection(name: Direction, mode: 'hold' | 'free' | number): void;
  /** held-direction residuals in m or rad; null for directions not held (free or accelerated). */
  residuals(): Record<Direction, number | null>;
  energy(): { kinetic: number; potential: number; total: number };
  /** names of the joints at or past a limit after the last step (a copy; [] under limits 'ignore'). */
  limitHits(): string[];
  /** of the solve at the start of the last step (copies). */
  nu(): number[];
  jointTorques(): number[];
  qdd(): number[];
  /** link: index after the root or link name; wrench in base orientation about the link origin. */
  setExternalWrench(link: number | string, wrench: Vec): void;
  delete(): void;
}

export interface Robot {
  readonly root: string;
  readonly tip: string;
  readonly numJoints: number;
  /** links after the root (fixed-joint links included). */
  readonly numLinks: number;
  readonly jointNames: string[];
  readonly jointTypes: Array<'revolute' | 'continuous' | 'prismatic'>;
  readonly limits: JointLimits[];
  readonly damping: number[];
  readonly friction: number[];
  /** links after the root, root to tip (the tip last). */
  readonly linkNames: string[];
  readonly deleted: boolean;
  solve(c: Case, options?: SolveOptions): Result;
  forwardKinematics(q: Vec): LinkPose[];
  /** 6 rows (linear first) x numJoints: [v; w] of the tip link's origin, base orientation. */
  tipJacobian(q: Vec): number[][];
  /** M(q), rotor inertia included unless rotorInertia is false. */
  massMatrix(q: Vec, options?: { rotorInertia?: boolean }): number[][];
  /** joint torques producing qdd at (q, qd) under gravity (default [0, 0, -9.81]) and f_ext. */
  rnea(q: Vec, qd: Vec, qdd: Vec, options?: { gravity?: Vec; f_ext?: Vec[]; effects?: Effects | number; frictionVelocity?: number }): number[];
  createSolver(options?: SolverOptions): Solver;
  createSimulator(options?: SimulatorOptions): Simulator;
  /** solvers and simulators created from the robot stay valid. */
  delete(): void;
}

export interface LoadOptions {
  root: string;
  tip: string;
  /** a joint of the chain with a <mimic> element: an Error naming it ('error', the
   * default) or a joint of its own, as KDL loads it ('independent'). */
  mimic?: 'error' | 'independent';
}

export interface Achd {
  loadURDF(text: string, options: LoadOptions): Robot;
  /** bytes of wasm memory (grows, never shrinks). */
  memoryBytes(): number;
  /** the effect bits, for SolveOptions.effects as a number. */
  readonly Effects: Readonly<Record<keyof Effects, number>>;
}

export default function createAchd(moduleOverrides?: object): Promise<Achd>;
