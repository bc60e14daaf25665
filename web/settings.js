// What the user chose on the page (robot, directions and which of them yield to pushes,
// prescribed joints, effects, integrator, dt, the singularity policy and the adaptive
// integrator's relative tolerance), its defaults, and its round trip through the URL hash
// so that a view can be shared, e.g.
// #robot=ur5&integrator=rk4&dt=0.001&effects=gravity,velocity_products,damping&dirs=z:hold,rx:0.5&yield=z
// (prescribed joints belong to the robot's run and are not in the hash). `dirs` and
// `yield` are the selected link's: a chain's tip, or the link `link=` names (a tree's
// other default links are held as the robot list holds them). An own URDF is
// robot=custom&urdf=<deflate:… or local:…, web/urdf_share.js>&root=<link>&tip=<link> (no
// tip: the whole robot; base=floating: on a floating base, standing on its feet) and the
// other options the page gave loadURDF: mimic=, inertia=, srdf=<deflate:… or local:…, the
// SRDF's group_states> and pose=<its group_state the robot starts from>. The loop joints
// the user closed on the page are closed=<JSON: [[name, link_a, link_b, xyz, rpy], ...]>,
// each a fixed loop joint whose frame a is link_a's frame and whose frame b sits at xyz,
// rpy in link_b's frame (web/loop_pick.js).
// Values are the scene files' words (achd.constants); the simulator's option keys are
// the same words in camelCase. Which directions, effects, integrators and policies exist,
// which integrators are adaptive, gravity and the defaults are the module's (`offer`,
// web/module_offer.js, taken by adoptOffer() once the module has loaded): this file keeps
// no list of its own, only the words it shows for some names.

// The module's directions, the effects the page switches ({key: the simulator's option
// key, hash: the scene files' name, label}), and its gravity: set by adoptOffer().
export let DIRECTIONS = [];
export let EFFECTS = [];
export let GRAVITY = [];
let adaptiveIntegrators = [];

// Effects the page keeps on whatever the user picks (no switch): the rotor inertia is the
// robot's, and constraints are what the page is about.
const ALWAYS_ON = ['rotor_inertia', 'constraints'];
// How the page names some effects; any other is shown by its name.
const EFFECT_LABELS = { velocity_products: 'velocity products', damping: 'joint damping', friction: 'joint friction',
  external_wrenches: 'external push' };
const camelCase = (name) => name.replace(/_([a-z])/g, (_, ch) => ch.toUpperCase());

// Takes what the module offers (moduleOffer(achd)): call once it has loaded, before
// anything here or the controls are used.
export function adoptOffer(offer) {
  DIRECTIONS = [...offer.directions];
  EFFECTS = offer.effects.filter((name) => !ALWAYS_ON.includes(name))
    .map((name) => ({ key: camelCase(name), hash: name, label: EFFECT_LABELS[name] ?? name.replaceAll('_', ' ') }));
  GRAVITY = [...offer.gravity];
  adaptiveIntegrators = [...offer.adaptiveIntegrators];
}

// Hash words of the previous release, still read (links already shared), never written.
const OLD_HASH_WORDS = {
  integrator: { 'semi-implicit': 'semi_implicit_euler', euler: 'explicit_euler' },
  effects: { velocity: 'velocity_products', push: 'external_wrenches' },
};
const current = (kind, word) => (Object.hasOwn(OLD_HASH_WORDS[kind], word) ? OLD_HASH_WORDS[kind][word] : word);
export const TIME_STEPS = [0.00025, 0.0005, 0.001, 0.002, 0.005, 0.01];
export const RELATIVE_TOLERANCES = [1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10];

// offer: {integrators, policies, defaults: {integrator, policy, rtol}} (web/module_offer.js).
// rtol is kept whatever the integrator, so that switching back to an adaptive one restores
// it; it reaches the simulator and the hash only with an adaptive integrator.
export function defaultSettings(robot, offer) {
  return {
    robot,
    integrator: offer.defaults.integrator,
    dt: 0.001,
    policy: offer.defaults.policy,
    rtol: offer.defaults.rtol,
    // the joint-limit policy ('report', 'clamp', 'ignore'); null: the simulator's default
    limits: null,
    effects: Object.fromEntries(EFFECTS.map((e) => [e.key, true])),
    // the link the directions below are of: null for a chain's tip (a tree: its first
    // default link), else a link name
    link: null,
    directions: Object.fromEntries(DIRECTIONS.map((d) => [d, 'free'])),
    // true: the direction yields to pushes (its w_fext is 0, sim.setDirectionWeights)
    yielding: Object.fromEntries(DIRECTIONS.map((d) => [d, false])),
    // joint name -> {motion, position, velocity, amplitude, frequency, phase} in page time
    prescribed: {},
    // the loop joints the user closed on the page (loadURDF's loops, web/loop_pick.js)
    closed: [],
    // an own URDF's place in the link: {ref (urdf=), root, tip (null: the whole robot),
    // floating, mimic, inertia, srdf (srdf=: its SRDF's ref), pose} (OWN_OPTIONS: absent
    // or null when not given), or null
    own: null,
  };
}

// Prescribed joint motion on the page: the kinds (achd.constants.motion_kinds) and the
// parameters each reads. The page starts a motion where the joint is when it is applied.
export const MOTION_PARAMETERS = { constant: ['position'], ramp: ['position', 'velocity'],
  sine: ['position', 'amplitude', 'frequency'] };

// The motion the simulator follows for a joint at q when the user applies {motion,
// position, velocity, amplitude, frequency} at page time t: a ramp and a sine pass through
// their given position then (the sine at its centre, rising).
export function motionFrom(params, t) {
  const kind = params.motion;
  if (!Object.hasOwn(MOTION_PARAMETERS, kind)) throw new Error(`unknown motion "${kind}" (constant, ramp or sine)`);
  const m = { motion: kind };
  for (const key of MOTION_PARAMETERS[kind]) {
    const v = params[key];
    if (typeof v !== 'number' || !Number.isFinite(v)) throw new Error(`${kind} motion: ${key} must be a finite number`);
    m[key] = v;
  }
  if (kind === 'sine' && m.frequency < 0) throw new Error('sine motion: frequency must be >= 0 (Hz)');
  if (kind === 'ramp') m.position -= m.velocity * t;
  if (kind === 'sine') m.phase = -2 * Math.PI * m.frequency * t;
  return m;
}

// The same motion in a simulator's own time, which started at page time t0.
export function motionInSimulatorTime(m, t0) {
  const out = { ...m };
  if (m.motion === 'ramp') out.position = m.position + m.velocity * t0;
  if (m.motion === 'sine') out.phase = m.phase + 2 * Math.PI * m.frequency * t0;
  return out;
}

// The integrators that take a relative tolerance (rtol): the error-controlled ones.
export const isAdaptive = (integrator) => adaptiveIntegrators.includes(integrator);

// The options of robot.createSimulator for these settings, as the page creates it.
export function simulatorOptions(s) {
  const options = {
    integrator: s.integrator,
    effects: { ...s.effects, ...Object.fromEntries(ALWAYS_ON.map((name) => [camelCase(name), true])) },
    gravity: GRAVITY,
    policy: s.policy,
  };
  if (isAdaptive(s.integrator)) options.rtol = s.rtol;
  if (s.limits) options.limits = s.limits;
  return options;
}

// A direction mode is 'free', 'hold' or a finite number (classical acceleration setpoint).
export function checkDirection(name, mode) {
  if (!DIRECTIONS.includes(name)) {
    throw new Error(`unknown direction "${name}" (expected one of ${DIRECTIONS.join(', ')})`);
  }
  if (mode !== 'free' && mode !== 'hold' && !(typeof mode === 'number' && Number.isFinite(mode))) {
    throw new Error(`direction ${name}: mode must be 'free', 'hold' or a finite number, got ${String(mode)}`);
  }
}

// The loadURDF options of an own URDF that the link carries besides urdf=, root=, tip=
// and base=, under their loadURDF names (srdf: the ref of its SRDF, web/urdf_share.js).
export const OWN_OPTIONS = ['mimic', 'inertia', 'srdf', 'pose'];

// Whether two own URDFs of links ({ref, root, tip, floating, ...OWN_OPTIONS}) are the same
// robot set up the same way.
export function sameOwn(a, b) {
  if (!a || !b) return a === b;
  return ['ref', 'root', 'tip', 'floating', ...OWN_OPTIONS].every((k) => (a[k] ?? null) === (b[k] ?? null));
}

export function formatHash(s) {
  const params = new URLSearchParams();
  params.set('robot', s.robot);
  if (s.own) {
    params.set('urdf', s.own.ref);
    params.set('root', s.own.root);
    if (s.own.tip) params.set('tip', s.own.tip);
    if (s.own.floating) params.set('base', 'floating');
    for (const key of OWN_OPTIONS) if (s.own[key]) params.set(key, s.own[key]);
  }
  params.set('integrator', s.integrator);
  if (isAdaptive(s.integrator)) params.set('rtol', String(s.rtol));
  params.set('dt', String(s.dt));
  params.set('policy', s.policy);
  if (s.limits) params.set('limits', s.limits);
  params.set('effects', EFFECTS.filter((e) => s.effects[e.key]).map((e) => e.hash).join(','));
  if (s.link) params.set('link', s.link);
  const dirs = DIRECTIONS.filter((d) => s.directions[d] !== 'free').map((d) => `${d}:${s.directions[d]}`);
  if (dirs.length) params.set('dirs', dirs.join(','));
  const yielding = DIRECTIONS.filter((d) => s.yielding[d]);
  if (yielding.length) params.set('yield', yielding.join(','));
  if (s.closed.length) {
    params.set('closed', JSON.stringify(s.closed.map((l) => [l.name, l.link_a, l.link_b, l.origin_b.xyz, l.origin_b.rpy])));
  }
  // URLSearchParams escapes ':' and ','; they are legal in a fragment and easier to read.
  return '#' + params.toString().replaceAll('%3A', ':').replaceAll('%2C', ',');
}

// The robot a hash names, or the fallback: the page fetches its URDF while the module
// that the rest of the hash is checked against still loads.
export function hashRobot(hash, fallback) {
  return new URLSearchParams(hash.replace(/^#/, '')).get('robot') ?? fallback;
}

// The own URDF a hash names, {ref, root, tip (null: the whole robot), floating, mimic,
// inertia, srdf, pose (each only when given)} (urdf= and root= given), or null.
export function hashOwn(hash) {
  const params = new URLSearchParams(hash.replace(/^#/, ''));
  const [ref, root, tip] = ['urdf', 'root', 'tip'].map((k) => params.get(k));
  if (ref === null || root === null) return null;
  return { ref, root, tip, floating: params.get('base') === 'floating',
    ...Object.fromEntries(OWN_OPTIONS.filter((k) => params.has(k)).map((k) => [k, params.get(k)])) };
}

// Reads a hash over the defaults, taking only names the module offers; returns the
// settings and the complaints about parts it ignored, so the page can say why a shared
// link did not fully apply.
export function parseHash(hash, defaults, offer) {
  const s = structuredClone(defaults);
  const problems = [];
  const params = new URLSearchParams(hash.replace(/^#/, ''));
  if (params.has('robot')) s.robot = params.get('robot');
  if (params.has('urdf')) {
    s.own = hashOwn(hash);
    if (!s.own) problems.push('urdf= needs root= (the own URDF\'s root link; tip= for a chain)');
  }
  if (params.has('integrator')) {
    const v = current('integrator', params.get('integrator'));
    if (offer.integrators.includes(v)) s.integrator = v;
    else problems.push(`unknown integrator "${v}"`);
  }
  if (params.has('rtol')) {
    const v = Number(params.get('rtol'));
    if (Number.isFinite(v) && v > 0 && v < 1) s.rtol = v;
    else problems.push(`rtol must be a number in (0, 1), got "${params.get('rtol')}"`);
  }
  if (params.has('dt')) {
    const v = Number(params.get('dt'));
    if (TIME_STEPS.includes(v)) s.dt = v;
    else problems.push(`dt must be one of ${TIME_STEPS.join(', ')} s`);
  }
  if (params.has('policy')) {
    const v = params.get('policy');
    if (offer.policies.includes(v)) s.policy = v;
    else problems.push(`unknown policy "${v}"`);
  }
  if (params.has('limits')) {
    const v = params.get('limits');
    if ((offer.limitPolicies ?? []).includes(v)) s.limits = v;
    else problems.push(`unknown joint-limit policy "${v}"`);
  }
  if (params.has('effects')) {
    const on = new Set(params.get('effects').split(',').filter(Boolean).map((w) => current('effects', w)));
    for (const e of EFFECTS) s.effects[e.key] = on.delete(e.hash);
    for (const name of on) problems.push(`unknown effect "${name}"`);
  }
  if (params.has('link')) s.link = params.get('link');
  if (params.has('dirs')) {
    for (const item of params.get('dirs').split(',').filter(Boolean)) {
      const [name, raw] = item.split(':');
      const mode = raw === 'hold' || raw === 'free' ? raw : Number(raw);
      try {
        checkDirection(name, mode);
        s.directions[name] = mode;
      } catch (err) {
        problems.push(err.message);
      }
    }
  }
  if (params.has('yield')) {
    for (const name of params.get('yield').split(',').filter(Boolean)) {
      if (DIRECTIONS.includes(name)) s.yielding[name] = true;
      else problems.push(`yield: unknown direction "${name}"`);
    }
  }
  if (params.has('closed')) {
    try {
      s.closed = closedLoops(params.get('closed'));
    } catch (err) {
      problems.push(`closed: ${err.message}`);
    }
  }
  return { settings: s, problems };
}

// Whether two lists of closed loops (settings.closed) are the same.
export function sameClosed(a, b) {
  return JSON.stringify(a) === JSON.stringify(b);
}

// The loops of a closed= value: fixed loop joints as web/loop_pick.js makes them. Throws
// an Error saying what is wrong with the value.
function closedLoops(value) {
  let list;
  try {
    list = JSON.parse(value);
  } catch {
    throw new Error('expected a JSON list of [name, link_a, link_b, [x, y, z], [roll, pitch, yaw]]');
  }
  if (!Array.isArray(list)) throw new Error('expected a JSON list of [name, link_a, link_b, [x, y, z], [roll, pitch, yaw]]');
  const triple = (v) => Array.isArray(v) && v.length === 3 && v.every((x) => typeof x === 'number' && Number.isFinite(x));
  return list.map((item, i) => {
    if (!Array.isArray(item) || item.length !== 5 || !item.slice(0, 3).every((x) => typeof x === 'string' && x) ||
        !triple(item[3]) || !triple(item[4])) {
      throw new Error(`loop ${i}: expected [name, link_a, link_b, [x, y, z], [roll, pitch, yaw]] with finite numbers`);
    }
    const [name, linkA, linkB, xyz, rpy] = item;
    return { name, type: 'fixed', link_a: linkA, origin_a: { xyz: [0, 0, 0], rpy: [0, 0, 0] },
      link_b: linkB, origin_b: { xyz, rpy } };
  });
}
