// Loading the user's own URDF: a file picker (one URDF or several files together), a
// folder picker and drag-and-drop anywhere on the page (files or folders) read the URDF,
// then a small form offers root and tip from the file's links (the longest chain
// preselected) and hands the choice to `onLoad(text, root, tip, fileName, files)`, files
// being the PickedFiles its meshes are looked up in (web/mesh_files.js).
import { PickedFiles, droppedFiles, pickedFiles } from './mesh_files.js';
import { chainLinks, longestChain, urdfTree } from './urdf_tree.js';
import { URDF_LIMIT_BYTES } from './urdf_share.js';

const URDF_NAME = /\.urdf$/i;
const XML_NAME = /\.xml$/i;

export class UrdfUpload {
  constructor({ onLoad, onError }) {
    this.onError = onError;
    this.form = document.getElementById('urdf-chain');
    this.fileLabel = document.getElementById('urdf-chain-file');
    this.root = document.getElementById('urdf-root');
    this.tip = document.getElementById('urdf-tip');
    for (const id of ['urdf-file', 'urdf-folder']) {
      const picker = document.getElementById(id);
      picker.addEventListener('change', () => {
        if (picker.files.length) this.read(pickedFiles(picker.files));
        picker.value = '';  // choosing the same files again should reload them
      });
    }
    this.form.addEventListener('submit', (e) => {
      e.preventDefault();
      onLoad(this.text, this.root.value, this.tip.value, this.fileName, this.files);
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
      droppedFiles(e.dataTransfer).then((files) => this.read(files), (err) => this.onError(err));
    });
  }

  // files: [{path, file}] picked or dropped together; the URDF among them is read.
  async read(files) {
    const urdf = chooseUrdf(files);
    if (!urdf) {
      this.form.hidden = true;
      this.onError(new Error(`no .urdf file among the ${files.length} file(s) given ` +
        '(a .xacro file must be expanded with xacro first)'));
      return;
    }
    try {
      // The command line's limit on a URDF file: a larger one is not read into the tab.
      if (urdf.file.size > URDF_LIMIT_BYTES) {
        throw new Error(`${urdf.file.size} bytes, larger than the ${URDF_LIMIT_BYTES / (1024 * 1024)} MiB limit ` +
          'of a URDF file');
      }
      this.text = await urdf.file.text();
      this.fileName = urdf.path;
      this.tree = urdfTree(this.text);
    } catch (err) {
      this.form.hidden = true;
      this.onError(new Error(`${urdf.path}: ${err.message}`));
      return;
    }
    this.files = new PickedFiles(files, urdf.path);
    const { root, tip } = longestChain(this.tree);
    this.root.replaceChildren(...this.tree.links.map((l) => new Option(l, l, false, l === root)));
    this.offerTips(tip);
    const others = files.length - 1;
    this.fileLabel.textContent = `${urdf.path}${others ? ` (and ${others} more file${others > 1 ? 's' : ''})` : ''}: choose the chain`;
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

// The URDF among files given together: a .urdf file (else an .xml one), the one nearest
// the top of the folder, then the first by name.
function chooseUrdf(files) {
  for (const pattern of [URDF_NAME, XML_NAME]) {
    const candidates = files.filter((f) => pattern.test(f.path));
    candidates.sort((a, b) => depth(a.path) - depth(b.path) || a.path.localeCompare(b.path));
    if (candidates.length) return candidates[0];
  }
  return null;
}

function depth(path) {
  return path.split('/').length;
}
