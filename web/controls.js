// The control panel: play/pause/step/reset, integrator and dt, the six tip-direction
// toggles (free / hold / acceleration setpoint) and the effect switches. It reports the
// user's changes through `on` callbacks and shows whatever settings it is given.
import { DIRECTIONS, EFFECTS } from './settings.js';
import { DIRECTION_COLORS } from './chain_view.js';

const DIRECTION_TITLES = {
  x: 'linear x', y: 'linear y', z: 'linear z', rx: 'angular x', ry: 'angular y', rz: 'angular z',
};

export class Controls {
  // on: {playPause(), step(), reset(), integrator(v), dt(v), direction(name, mode), effect(key, on)}
  constructor(on) {
    this.playButton = document.getElementById('btn-play');
    this.playButton.addEventListener('click', () => on.playPause());
    document.getElementById('btn-step').addEventListener('click', () => on.step());
    document.getElementById('btn-reset').addEventListener('click', () => on.reset());
    this.integrator = document.getElementById('integrator');
    this.integrator.addEventListener('change', () => on.integrator(this.integrator.value));
    this.dt = document.getElementById('dt');
    this.dt.addEventListener('change', () => on.dt(Number(this.dt.value)));

    this.rows = {};
    const table = document.getElementById('directions');
    for (const name of DIRECTIONS) {
      const tr = table.insertRow();
      const label = tr.insertCell();
      label.className = 'name';
      label.title = DIRECTION_TITLES[name];
      const swatch = document.createElement('span');
      swatch.className = 'swatch';
      swatch.style.background = DIRECTION_COLORS[name];
      label.append(swatch, name);

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
      this.rows[name] = { buttons, input };
    }

    this.effectBoxes = {};
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

  show(settings, playing) {
    this.playButton.textContent = playing ? 'Pause' : 'Play';
    this.integrator.value = settings.integrator;
    this.dt.value = String(settings.dt);
    for (const name of DIRECTIONS) {
      const mode = settings.directions[name];
      const row = this.rows[name];
      const key = typeof mode === 'number' ? 'accel' : mode;
      for (const [m, b] of Object.entries(row.buttons)) b.setAttribute('aria-pressed', String(m === key));
      row.input.disabled = key !== 'accel';
      if (key === 'accel' && Number(row.input.value) !== mode) row.input.value = String(mode);
    }
    for (const e of EFFECTS) this.effectBoxes[e.key].checked = settings.effects[e.key];
  }
}
