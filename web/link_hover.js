// The name of the link under the pointer, in a small label beside it; over something
// `describe` knows (the force arrows), its text instead.
export class LinkHover {
  // view: ChainView; nameOf(link) gives the name of an FK index (root = 0);
  // describe(clientX, clientY) gives a text for the pointer there, or null.
  constructor(view, label, nameOf, describe = () => null) {
    if (!view.enabled) return;
    const canvas = view.renderer.domElement;
    canvas.addEventListener('pointermove', (e) => {
      let text = e.buttons ? null : describe(e.clientX, e.clientY);
      if (!text) {
        const hit = e.buttons ? null : view.pick(e.clientX, e.clientY);
        text = hit ? nameOf(hit.link) : null;
      }
      label.hidden = !text;
      if (!text) return;
      const box = label.offsetParent.getBoundingClientRect();
      label.textContent = text;
      label.style.left = `${e.clientX - box.left}px`;
      label.style.top = `${e.clientY - box.top}px`;
    });
    canvas.addEventListener('pointerleave', () => (label.hidden = true));
  }
}
