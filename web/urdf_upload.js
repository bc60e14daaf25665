// Loading the user's own URDF: a file picker and drag-and-drop anywhere on the page
// read the text, then a small form offers root and tip from the file's links (the
// longest chain preselected) and hands the choice to `onLoad(text, root, tip, fileName)`.
import { chainLinks, longestChain, urdfTree } from './urdf_tree.js';

export class UrdfUpload {
  constructor({ onLoad, onError }) {
    this.onError = onError;
    this.form = document.getElementById('urdf-chain');
    this.fileLabel = document.getElementById('urdf-chain-file');
    this.root = document.getElementById('urdf-root');
    this.tip = document.getElementById('urdf-tip');
    const picker = document.getElementById('urdf-file');
    picker.addEventListener('change', () => {
      if (picker.files[0]) this.read(picker.files[0]);
      picker.value = '';  // choosing the same file again should reload it
    });
    this.form.addEventListener('submit', (e) => {
      e.preventDefault();
      onLoad(this.text, this.root.value, this.tip.value, this.fileName);
    });
    document.getElementById('urdf-cancel').addEventListener('click', () => {
      this.form.hidden = true;
    });
    this.root.addEventListener('change', () => this.offerTips());

    // Drag-and-drop: the overlay shows while a file is over the page.
    const overlay = document.getElementById('drop-overlay');
    let depth = 0;
    const hasFiles = (e) => [...(e.dataTransfer?.types ?? [])].includes('Files');
    window.addEventListener('dragenter', (e) => {
      if (!hasFiles(e)) return;
      depth++;
      overlay.hidden = false;
    });
    window.addEventListener('dragleave', () => {
      depth = Math.max(0, depth - 1);
      if (!depth) overlay.hidden = true;
    });
    window.addEventListener('dragover', (e) => {
      if (hasFiles(e)) e.preventDefault();
    });
    window.addEventListener('drop', (e) => {
      if (!hasFiles(e)) return;
      e.preventDefault();
      depth = 0;
      overlay.hidden = true;
      if (e.dataTransfer.files[0]) this.read(e.dataTransfer.files[0]);
    });
  }

  async read(file) {
    try {
      this.text = await file.text();
      this.fileName = file.name;
      this.tree = urdfTree(this.text);
    } catch (err) {
      this.form.hidden = true;
      this.onError(new Error(`${file.name}: ${err.message}`));
      return;
    }
    const { root, tip } = longestChain(this.tree);
    this.root.replaceChildren(...this.tree.links.map((l) => new Option(l, l, false, l === root)));
    this.offerTips(tip);
    this.fileLabel.textContent = `${file.name}: choose the chain`;
    this.form.hidden = false;
  }

  // Tips are the links below the chosen root.
  offerTips(preferred) {
    const root = this.root.value;
    const below = this.tree.links.filter((l) => l !== root && chainLinks(this.tree, root, l));
    const pick = below.includes(preferred) ? preferred : below[below.length - 1];
    this.tip.replaceChildren(...below.map((l) => new Option(l, l, false, l === pick)));
  }

  hide() {
    this.form.hidden = true;
  }
}
