// Joint torque bars: per movable joint, joint_torques of the simulator's last solve (the
// torques a controller must command, ff - J^T alpha nu) against the URDF's effort limit.
// A bar grows from the middle, right for a positive torque, left for a negative one; ticks
// mark plus and minus the effort limit (the track's half-width is 1.1 limits); past the
// limit the bar turns red, and it stops growing at the track's end. A joint whose URDF gives no effort limit (0 or absent) has no
// bar scale: only its number shows. Bars move by transform, written only when they change,
// and numbers at most every `NUMBERS_EVERY_MS`: a frame changes no layout.

const NUMBERS_EVERY_MS = 200;
// How far past the limit a bar is drawn, relative to it.
const DRAWN_PAST_LIMIT = 1.1;

export class TorqueBars {
  constructor(list) {
    this.list = list;
    this.rows = [];
    this.lastNumbers = -Infinity;
  }

  // robot: an achd robot (jointNames, jointTypes, limits). A floating base's free joint
  // has no bar (nothing actuates it); its six rates come first in joint_torques.
  setRobot(robot) {
    this.first = robot.floating ? 1 : 0;
    this.offset = robot.floating ? 5 : 0;  // jointNames index j -> joint_torques index j + offset
    this.rows = robot.jointNames.slice(this.first).map((name, i) => {
      const j = i + this.first;
      const effort = robot.limits[j].effort;
      const unit = robot.jointTypes[j] === 'prismatic' ? 'N' : 'N m';
      const row = document.createElement('div');
      row.className = 'torque-row';
      row.dataset.joint = name;
      const label = document.createElement('span');
      label.className = 'torque-name';
      label.textContent = name;
      label.title = effort > 0 ? `effort limit ${effort} ${unit} (URDF)` : 'no effort limit in the URDF';
      const track = document.createElement('span');
      track.className = 'torque-track';
      const bar = document.createElement('span');
      bar.className = 'torque-bar';
      if (effort > 0) track.append(bar);
      else track.classList.add('torque-unscaled');
      const value = document.createElement('span');
      value.className = 'torque-value';
      row.append(label, track, value);
      return { row, bar, value, effort, unit, over: false, torque: 0, fraction: 0, drawn: 0 };
    });
    this.list.replaceChildren(...this.rows.map((r) => r.row));
    this.lastNumbers = -Infinity;
  }

  // torques: joint_torques of the last solve (one per joint); now: performance.now().
  show(torques, now) {
    const numbers = now - this.lastNumbers >= NUMBERS_EVERY_MS;
    if (numbers) this.lastNumbers = now;
    for (let j = 0; j < this.rows.length; j++) {
      const r = this.rows[j];
      const tau = torques[j + this.first + this.offset];
      r.torque = tau;
      if (r.effort > 0) {
        r.fraction = tau / r.effort;
        const drawn = Math.max(-DRAWN_PAST_LIMIT, Math.min(DRAWN_PAST_LIMIT, r.fraction)) / DRAWN_PAST_LIMIT;
        if (drawn !== r.drawn) {
          r.drawn = drawn;
          r.bar.style.transform = `scaleX(${drawn})`;
        }
        const over = Math.abs(tau) > r.effort;
        if (over !== r.over) {
          r.over = over;
          r.row.classList.toggle('torque-over', over);
        }
      }
      if (numbers) {
        r.value.textContent = r.effort > 0
          ? `${tau.toFixed(tau === 0 || Math.abs(tau) >= 10 ? 1 : 2)} / ${r.effort} ${r.unit}`
          : `${tau.toFixed(2)} ${r.unit}`;
      }
    }
  }

  // Per joint: {joint, torque, effort, fraction of the limit (null without one), over}.
  state() {
    return this.rows.map((r) => ({
      joint: r.row.dataset.joint, torque: r.torque, effort: r.effort,
      fraction: r.effort > 0 ? r.fraction : null, over: r.over,
    }));
  }
}
