// The control panel: play/pause/step/reset, integrator, its relative tolerance (adaptive
// integrators), dt and the singularity policy, the six tip-direction toggles (free /
// hold / acceleration setpoint, and whether a held direction yields to pushes; a direction
// the simulator released is marked lost), prescribed joint motion and the effect switches. It reports the user's changes through `on` callbacks and shows
// whatever settings it is given.
import { DIRECTIONS, EFFECTS, MOTION_PARAMETERS, RELATIVE_TOLERANCES, isAdaptive } from './settings.js';
import { DIRECTION_COLORS } from './chain_view.js';

// Names the page knows how to say; any other name the module offers is shown as it is.
const INTEGRATOR_LABELS = {
  rk4: 'RK4',
  semi_implicit_euler: 'semi-implicit Euler',
  explicit_euler: 'explicit Euler',
  dormand_prince: 'Dormand-Prince (adaptive)',
  implicit_euler: 'implicit Euler',
};
const POLICY_LABELS = {
  variable_damping: 'variable damping',
  damped: 'damped',
  truncate: 'truncate',
};

const DIRECTION_TITLES = {
  x: 'linear x', y: 'linear y', z: 'linear z', rx: 'angular x', ry: 'angular y', rz: 'angular z',
};

export class Controls {
  // on: {playPause(), step(), reset(), integrator(v), rtol(v), dt(v), policy(v), limits(v),
  //      direction(name, mode), yield(name, on), prescribe(joint, params | null), effect(key, on)}
  constructor(on) {
    this.playButton = document.getElementById('btn-play');
    this.playButton.addEventListener('click', () => on.playPause());
    document.getElementById('btn-step').addEventListener('click', () => on.step());
    document.getElementById('btn-reset').addEventListener('click', () => on.reset());
    this.integrator = document.getElementById('integrator');
    this.integrator.addEventListener('change', () => on.integrator(this.integrator.value));
    this.rtol = document.getElementById('rtol');
    this.rtol.addEventListener('change', () => on.rtol(Number(this.rtol.value)));
    this.dt = document.getElementById('dt');
    this.dt.addEventListener('change', () => on.dt(Number(this.dt.value)));
    this.policy = document.getElementById('policy');
    this.policy.addEventListener('change', () => on.policy(this.policy.value));
    this.limits = document.getElementById('limits');
    this.limits.addEventListener('change', () => on.limits(this.limits.value));

    this.on = on;
    this.rows = {};  // per direction, built by offer()

    // Prescribed joint motion: a joint, its motion kind and the parameters that kind reads.
    this.jointSelect = document.getElementById('joint-select');
    this.jointMotion = document.getElementById('joint-motion');
    this.jointSummary = document.getElementById('joint-summary');
    this.jointInputs = Object.fromEntries(['position', 'velocity', 'amplitude', 'frequency']
      .map((key) => [key, document.getElementById(`joint-${key}`)]));
    this.jointMotion.addEventListener('change', () => {
      // A joint not yet prescribed starts its motion from where it is now.
      const q = this.jointQ(this.jointSelect.value);
      if (!this.prescribed[this.jointSelect.value] && q !== null) this.jointInputs.position.value = String(Number(q.toFixed(4)));
      this.showMotionParameters();
    });
    this.jointSelect.addEventListener('change', () => this.showJoint());
    document.getElementById('joint-apply').addEventListener('click', () => {
      const kind = this.jointMotion.value;
      if (kind === 'free') return on.prescribe(this.jointSelect.value, null);
      const params = { motion: kind };
      for (const key of MOTION_PARAMETERS[kind]) params[key] = Number(this.jointInputs[key].value);
      on.prescribe(this.jointSelect.value, params);
    });
    this.prescribed = {};
    this.jointQ = () => null;

    this.effectBoxes = {};  // per effect, built by offer()
  }

  // Fills the integrator, policy and joint-limit lists with what the module offers
  // (web/module_offer.js), and builds the direction rows and effect switches for the
  // directions and effects it offers (settings.js, after adoptOffer), once.
  offer(offer) {
    const on = this.on;
    if (!Object.keys(this.rows).length) {
      const table = document.getElementById('directions');
      for (const name of DIRECTIONS) {
        const tr = table.insertRow();
        const label = tr.insertCell();
        label.className = 'name';
        label.title = DIRECTION_TITLES[name];
        const swatch = document.createElement('span');
        swatch.className = 'swatch';
        swatch.style.background = DIRECTION_COLORS[name];
        const lostTag = document.createElement('span');
        lostTag.className = 'lost-tag';
        lostTag.textContent = 'lost';
        lostTag.hidden = true;
        label.append(swatch, name, lostTag);

        const modes = document.createElement('div');
        modes.className = 'modes';
        const buttons = {};
        for (const mode of ['free', 'hold', 'accel']) {
          const b = document.createElement('button');
          b.type = 'button';
          b.textContent = mode;
          b.dataset.direction = name;
          b.dataset.mode = mode;
          b.addEventListener('click', () => on.direction(name, mode === 'accel' ? Number(input.value) : mode));
          buttons[mode] = b;
          modes.append(b);
        }
        tr.insertCell().append(modes);

        const input = document.createElement('input');
        input.type = 'number';
        input.step = '0.1';
        input.value = '0';
        input.title = DIRECTION_TITLES[name] + (name.startsWith('r') ? ' acceleration, rad/s²' : ' acceleration, m/s²');
        input.addEventListener('change', () => {
          const v = Number(input.value);
          if (input.value !== '' && Number.isFinite(v)) on.direction(name, v);
        });
        tr.insertCell().append(input);

        const yieldLabel = document.createElement('label');
        yieldLabel.className = 'yield';
        yieldLabel.title = `yield to push: a push moves the tip along ${name} while it is held (w_fext = 0)`;
        const yieldBox = document.createElement('input');
        yieldBox.type = 'checkbox';
        yieldBox.dataset.yield = name;
        yieldBox.addEventListener('change', () => on.yield(name, yieldBox.checked));
        yieldLabel.append(yieldBox, ' yield');
        tr.insertCell().append(yieldLabel);
        this.rows[name] = { row: tr, label, lostTag, buttons, input, yieldBox };
      }
      const effects = document.getElementById('effects');
      for (const e of EFFECTS) {
        const label = document.createElement('label');
        const box = document.createElement('input');
        box.type = 'checkbox';
        box.dataset.effect = e.key;
        box.addEventListener('change', () => on.effect(e.key, box.checked));
        label.append(box, ' ', e.label);
        effects.append(label);
        this.effectBoxes[e.key] = box;
      }
    }
    this.integrator.replaceChildren(...offer.integrators.map((n) => new Option(INTEGRATOR_LABELS[n] ?? n, n)));
    this.policy.replaceChildren(...offer.policies.map((n) => new Option(POLICY_LABELS[n] ?? n, n)));
    this.limits.replaceChildren(...offer.limitPolicies.map((n) => new Option(n, n)));
    this.defaultLimits = offer.defaults.limits;
    this.rtol.replaceChildren(...RELATIVE_TOLERANCES.map((v) => new Option(v.toExponential(0), String(v))));
  }

  // The robot's joints; q(name): the joint's position now (the position a new motion
  // starts from).
  setJoints(names, q) {
    this.jointSelect.replaceChildren(...names.map((n) => new Option(n, n)));
    this.jointQ = q;
    this.showJoint();
  }

  // The selected joint's motion (or free), its parameters filled in.
  showJoint() {
    const m = this.prescribed[this.jointSelect.value];
    this.jointMotion.value = m ? m.motion : 'free';
    const q = this.jointQ(this.jointSelect.value);
    this.jointInputs.position.value = String(m?.position !== undefined && m.motion !== 'ramp' ? m.position
      : q === null ? 0 : Number(q.toFixed(4)));
    for (const key of ['velocity', 'amplitude', 'frequency'])
      if (m && m[key] !== undefined) this.jointInputs[key].value = String(m[key]);
    this.showMotionParameters();
  }

  showMotionParameters() {
    const read = MOTION_PARAMETERS[this.jointMotion.value] ?? [];
    for (const [key, input] of Object.entries(this.jointInputs)) input.closest('label').hidden = !read.includes(key);
  }

  show(settings, playing) {
    this.playButton.textContent = playing ? 'Pause' : 'Play';
    this.integrator.value = settings.integrator;
    this.dt.value = String(settings.dt);
    this.policy.value = settings.policy;
    this.limits.value = settings.limits ?? this.defaultLimits;
    // The tolerance is shown only for an adaptive integrator; a tolerance from a hash that
    // the list lacks gets an entry of its own.
    this.rtol.closest('label').hidden = !isAdaptive(settings.integrator);
    const rtol = String(settings.rtol);
    if (![...this.rtol.options].some((o) => o.value === rtol)) this.rtol.add(new Option(settings.rtol.toExponential(1), rtol));
    this.rtol.value = rtol;
    for (const name of DIRECTIONS) {
      const mode = settings.directions[name];
      const row = this.rows[name];
      const key = typeof mode === 'number' ? 'accel' : mode;
      for (const [m, b] of Object.entries(row.buttons)) b.setAttribute('aria-pressed', String(m === key));
      row.input.disabled = key !== 'accel';
      if (key === 'accel' && Number(row.input.value) !== mode) row.input.value = String(mode);
    }
    for (const e of EFFECTS) this.effectBoxes[e.key].checked = settings.effects[e.key];
    for (const name of DIRECTIONS) this.rows[name].yieldBox.checked = settings.yielding[name];
    const prescribed = Object.entries(settings.prescribed);
    this.jointSummary.textContent = prescribed.length
      ? `Prescribed: ${prescribed.map(([joint, m]) => `${joint} (${m.motion})`).join(', ')}.`
      : 'Every joint is driven by its torques.';
    const changed = JSON.stringify(this.prescribed) !== JSON.stringify(settings.prescribed);
    this.prescribed = structuredClone(settings.prescribed);
    if (changed) this.showJoint();
  }

  // lost: the directions the simulator has released (a 'released' event not yet followed
  // by 'resumed'); their rows are marked until the robot leaves the singular region.
  showLost(lost) {
    for (const name of DIRECTIONS) {
      const { row, label, lostTag } = this.rows[name];
      const isLost = lost.has(name);
      row.classList.toggle('lost', isLost);
      lostTag.hidden = !isLost;
      label.title = DIRECTION_TITLES[name] + (isLost ? ': lost (released by the simulator at a singular pose)' : '');
    }
  }
}
