// The name of the link under the pointer, in a small label beside it.
export class LinkHover {
  // view: ChainView; nameOf(link) gives the name of an FK index (root = 0).
  constructor(view, label, nameOf) {
    if (!view.enabled) return;
    const canvas = view.renderer.domElement;
    canvas.addEventListener('pointermove', (e) => {
      const hit = e.buttons ? null : view.pick(e.clientX, e.clientY);
      const name = hit ? nameOf(hit.link) : null;
      label.hidden = !name;
      if (!name) return;
      const box = label.offsetParent.getBoundingClientRect();
      label.textContent = name;
      label.style.left = `${e.clientX - box.left}px`;
      label.style.top = `${e.clientY - box.top}px`;
    });
    canvas.addEventListener('pointerleave', () => (label.hidden = true));
  }
}
