// The page's notice of simulation events: each time the simulator limited, released or
// resumed a held or accelerated direction near a configuration where the robot cannot
// follow it (sim.events(): {t, step, link, direction, kind, sigma_min, unmet, effort_ratio}; a loop joint's: loop
// instead of link), newest last, and
// which directions of each link are lost now (released and not yet resumed), for the
// toggles of the link they show.

// The list (and `recent`, for achdDemo.state()) keeps the newest events; a chattering
// boundary must not grow the page.
const MAX_SHOWN = 100;

const WHAT = {
  limited: 'limited (damped: the robot can only partly follow it here)',
  released: 'released (lost: the robot cannot follow it here)',
  resumed: 'resumed (followed again)',
};

export class EventsNotice {
  constructor(list, none) {
    this.list = list;
    this.none = none;
    this.clear();
  }

  clear() {
    this.recent = [];
    this.lost = new Map();  // link name -> Set of its lost direction names
    this.list.replaceChildren();
    this.none.hidden = false;
  }

  // events: new events in time order, t on the page's clock.
  add(events) {
    for (const e of events) {
      if (e.loop === undefined && e.kind === 'released') {
        if (!this.lost.has(e.link)) this.lost.set(e.link, new Set());
        this.lost.get(e.link).add(e.direction);
      } else if (e.loop === undefined && e.kind === 'resumed') {
        this.lost.get(e.link)?.delete(e.direction);
      }
      const item = document.createElement('li');
      item.className = e.kind;
      item.dataset.direction = e.direction;
      item.dataset.kind = e.kind;
      const sigma = Number.isFinite(e.sigma_min) ? `, σmin ${e.sigma_min.toExponential(1)}` : '';
      const unmet = e.kind !== 'resumed' && Number.isFinite(e.unmet) ? `, unmet ${e.unmet.toExponential(1)}` : '';
      const effort = e.effort_ratio > 1 ? `, effort ×${e.effort_ratio.toFixed(2)}` : '';
      const where = e.loop !== undefined ? `loop ${e.loop}` : e.link;
      item.textContent = `t = ${e.t.toFixed(3)} s (step ${e.step}): ${e.direction} ${WHAT[e.kind] ?? e.kind}` +
        ` at ${where}${sigma}${unmet}${effort}`;
      this.list.append(item);
      this.recent.push(e);
    }
    while (this.list.children.length > MAX_SHOWN) this.list.firstElementChild.remove();
    if (this.recent.length > MAX_SHOWN) this.recent.splice(0, this.recent.length - MAX_SHOWN);
    if (events.length) {
      this.none.hidden = true;
      this.list.scrollTop = this.list.scrollHeight;
    }
  }

  // The lost directions of `link` (a Set of names, empty when none).
  lostOn(link) {
    return this.lost.get(link) ?? new Set();
  }

  // A direction the user sets anew is no longer the simulator's lost one.
  forget(link, direction) {
    this.lost.get(link)?.delete(direction);
  }
}
