// What the user chose on the page (robot, directions, effects, integrator, dt), its
// defaults, and its round trip through the URL hash so that a view can be shared, e.g.
// #robot=ur5&integrator=rk4&dt=0.001&effects=gravity,velocity_products,damping&dirs=z:hold,rx:0.5
// Values are the scene files' words (achd.constants); the simulator's option keys are
// the same words in camelCase.

export const DIRECTIONS = ['x', 'y', 'z', 'rx', 'ry', 'rz'];

// Page effect toggles: `hash` is the scene files' name, `key` the simulator's.
export const EFFECTS = [
  { key: 'gravity', hash: 'gravity', label: 'gravity' },
  { key: 'velocityProducts', hash: 'velocity_products', label: 'velocity products' },
  { key: 'damping', hash: 'damping', label: 'joint damping' },
  { key: 'friction', hash: 'friction', label: 'joint friction' },
  { key: 'externalWrenches', hash: 'external_wrenches', label: 'external push' },
];

export const INTEGRATORS = ['rk4', 'semi_implicit_euler', 'explicit_euler'];

// Hash words of the previous release, still read (links already shared), never written.
const OLD_HASH_WORDS = {
  integrator: { 'semi-implicit': 'semi_implicit_euler', euler: 'explicit_euler' },
  effects: { velocity: 'velocity_products', push: 'external_wrenches' },
};
const current = (kind, word) => (Object.hasOwn(OLD_HASH_WORDS[kind], word) ? OLD_HASH_WORDS[kind][word] : word);
export const TIME_STEPS = [0.00025, 0.0005, 0.001, 0.002, 0.005, 0.01];

export function defaultSettings(robot) {
  return {
    robot,
    integrator: 'rk4',
    dt: 0.001,
    effects: Object.fromEntries(EFFECTS.map((e) => [e.key, true])),
    directions: Object.fromEntries(DIRECTIONS.map((d) => [d, 'free'])),
  };
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

export function formatHash(s) {
  const params = new URLSearchParams();
  params.set('robot', s.robot);
  params.set('integrator', s.integrator);
  params.set('dt', String(s.dt));
  params.set('effects', EFFECTS.filter((e) => s.effects[e.key]).map((e) => e.hash).join(','));
  const dirs = DIRECTIONS.filter((d) => s.directions[d] !== 'free').map((d) => `${d}:${s.directions[d]}`);
  if (dirs.length) params.set('dirs', dirs.join(','));
  // URLSearchParams escapes ':' and ','; they are legal in a fragment and easier to read.
  return '#' + params.toString().replaceAll('%3A', ':').replaceAll('%2C', ',');
}

// Reads a hash over the defaults; returns the settings and the complaints about parts
// it ignored, so the page can say why a shared link did not fully apply.
export function parseHash(hash, defaults) {
  const s = structuredClone(defaults);
  const problems = [];
  const params = new URLSearchParams(hash.replace(/^#/, ''));
  if (params.has('robot')) s.robot = params.get('robot');
  if (params.has('integrator')) {
    const v = current('integrator', params.get('integrator'));
    if (INTEGRATORS.includes(v)) s.integrator = v;
    else problems.push(`unknown integrator "${v}"`);
  }
  if (params.has('dt')) {
    const v = Number(params.get('dt'));
    if (TIME_STEPS.includes(v)) s.dt = v;
    else problems.push(`dt must be one of ${TIME_STEPS.join(', ')} s`);
  }
  if (params.has('effects')) {
    const on = new Set(params.get('effects').split(',').filter(Boolean).map((w) => current('effects', w)));
    for (const e of EFFECTS) s.effects[e.key] = on.delete(e.hash);
    for (const name of on) problems.push(`unknown effect "${name}"`);
  }
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
  return { settings: s, problems };
}
