// Choosing the link whose directions the controls show: a click on a link (a press and
// release without moving the pointer, so that orbiting and pushing stay drags) selects it;
// with Shift held, the directions also act at the point clicked instead of the origin.
// With Alt held, the click picks a link for a loop joint instead (two Alt-clicks close a
// loop between the two links).
const CLICK_PIXELS = 4;

export class LinkSelect {
  // view: ChainView; onSelect(link, point): called with the FK index (root = 0) of the link
  // clicked and, with Shift, the world point clicked (a THREE.Vector3), else null;
  // onLoopPick(link): called with the FK index of the link Alt-clicked.
  constructor(view, onSelect, onLoopPick) {
    this.press = null;
    if (!view.enabled) return;
    // Capture phase on the container: PushDrag stops a press on a link from reaching the
    // canvas, not from reaching this listener.
    view.container.addEventListener('pointerdown', (e) => {
      this.press = e.button === 0 ? { x: e.clientX, y: e.clientY, hit: view.pick(e.clientX, e.clientY) } : null;
    }, { capture: true });
    view.container.addEventListener('pointerup', (e) => {
      const p = this.press;
      this.press = null;
      if (!p?.hit || Math.hypot(e.clientX - p.x, e.clientY - p.y) > CLICK_PIXELS) return;
      if (e.altKey) onLoopPick(p.hit.link);
      else onSelect(p.hit.link, e.shiftKey ? p.hit.point : null);
    }, { capture: true });
  }
}
