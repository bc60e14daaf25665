// Loading the user's own URDF: a file picker (one URDF or several files together), a
// folder picker and drag-and-drop anywhere on the page (files or folders) read the URDF,
// then a small form offers: which URDF (a list when several were given), the whole robot
// or a chain (root and tip from the file's links, the longest chain preselected), a fixed
// or floating base, the mimic and inertia options and, when an .srdf file came along, its
// named poses; it hands the choice to `onLoad({text, fileName, files, root, tip (null: the
// whole robot), floating, mimic, inertia, srdf (text), srdfShared (the part of it a share
// link carries: its group_states), pose})`, files being the
// PickedFiles its meshes are looked up in (web/mesh_files.js). A URDF whose movable
// joints all lie on one chain is offered as that chain, a branching one whole.
import { PickedFiles, droppedFiles, pickedFiles } from './mesh_files.js';
import { srdfGroupStates, srdfPoses } from './srdf_poses.js';
import { chainLinks, isMovable, longestChain, urdfTree } from './urdf_tree.js';
import { URDF_LIMIT_BYTES } from './urdf_share.js';

const URDF_NAME = /\.urdf$/i;
const XML_NAME = /\.xml$/i;
const SRDF_NAME = /\.srdf$/i;
// The pose option of no SRDF pose: every joint at 0, or the middle of its limits.
const NO_POSE = '';

export class UrdfUpload {
  constructor({ onLoad, onError }) {
    this.onError = onError;
    this.form = document.getElementById('urdf-chain');
    this.fileLabel = document.getElementById('urdf-chain-file');
    this.root = document.getElementById('urdf-root');
    this.tip = document.getElementById('urdf-tip');
    this.pick = document.getElementById('urdf-pick');
    this.whole = document.getElementById('urdf-whole');
    this.base = document.getElementById('urdf-base');
    this.mimic = document.getElementById('urdf-mimic');
    this.inertia = document.getElementById('urdf-inertia');
    this.pose = document.getElementById('urdf-pose');
    for (const id of ['urdf-file', 'urdf-folder']) {
      const picker = document.getElementById(id);
      picker.addEventListener('change', () => {
        if (picker.files.length) this.read(pickedFiles(picker.files));
        picker.value = '';  // choosing the same files again should reload them
      });
    }
    this.form.addEventListener('submit', (e) => {
      e.preventDefault();
      // Without a pose chosen, the SRDF of the URDF's robot (or the first) still comes
      // along: its poses can be chosen once the robot is loaded.
      const pose = this.pose.value === NO_POSE ? null : this.poses[Number(this.pose.value)];
      const srdf = pose?.srdf ?? this.srdfOrder[0]?.text;
      onLoad({ text: this.text, fileName: this.fileName, files: this.files, root: this.root.value,
        tip: this.whole.value === 'chain' ? this.tip.value : null, floating: this.base.value === 'floating',
        mimic: this.mimic.value, inertia: this.inertia.value, srdf, srdfShared: srdf && srdfGroupStates(srdf),
        pose: pose?.name });
    });
    document.getElementById('urdf-cancel').addEventListener('click', () => {
      this.form.hidden = true;
    });
    this.root.addEventListener('change', () => this.offerTips());
    this.whole.addEventListener('change', () => this.showTip());
    this.pick.addEventListener('change', () => this.readUrdf(this.urdfs[Number(this.pick.value)]));

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

  // files: [{path, file}] picked or dropped together; their URDFs are offered (in
  // urdfFiles' order) and the first is read, with the poses of their SRDFs.
  async read(files) {
    this.urdfs = urdfFiles(files);
    if (!this.urdfs.length) {
      this.form.hidden = true;
      this.onError(new Error(`no .urdf file among the ${files.length} file(s) given ` +
        '(a .xacro file must be expanded with xacro first)'));
      return;
    }
    this.given = files;
    this.srdfs = [];
    for (const f of files.filter((f) => SRDF_NAME.test(f.path))) {
      try {
        const text = await f.file.text();
        this.srdfs.push({ path: f.path, text, ...srdfPoses(text) });
      } catch (err) {
        this.onError(new Error(`${f.path}: ${err.message}`));
      }
    }
    this.pick.replaceChildren(...this.urdfs.map((u, i) => new Option(u.path, String(i))));
    document.getElementById('urdf-pick-label').hidden = this.urdfs.length < 2;
    await this.readUrdf(this.urdfs[0]);
  }

  // Reads one URDF of the files given and fills the form for it.
  async readUrdf(urdf) {
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
    this.files = new PickedFiles(this.given, urdf.path);
    const { root, tip } = longestChain(this.tree);
    this.root.replaceChildren(...this.tree.links.map((l) => new Option(l, l, false, l === root)));
    this.offerTips(tip);
    const onChain = chainLinks(this.tree, root, tip).filter((l) => isMovable(this.tree, l)).length;
    const movable = this.tree.links.filter((l) => isMovable(this.tree, l)).length;
    this.whole.value = onChain === movable ? 'chain' : 'tree';
    this.showTip();
    this.offerPoses();
    const others = this.given.length - 1;
    this.fileLabel.textContent = `${urdf.path}${others ? ` (and ${others} more file${others > 1 ? 's' : ''})` : ''}:`;
    this.form.hidden = false;
  }

  // The SRDFs' poses, those of an SRDF of the URDF's robot (<robot name>) first and the
  // first of them chosen; none when no SRDF came along.
  offerPoses() {
    const name = new DOMParser().parseFromString(this.text, 'application/xml').documentElement.getAttribute('name');
    const srdfs = [...this.srdfs].sort((a, b) => Number(b.robot === name) - Number(a.robot === name));
    this.srdfOrder = srdfs;
    this.poses = srdfs.flatMap((s) => s.poses.map((pose) => ({ srdf: s.text, name: pose, path: s.path })));
    const several = srdfs.length > 1;
    this.pose.replaceChildren(new Option('none (joints at 0 or mid-limits)', NO_POSE),
      ...this.poses.map((p, i) => new Option(several ? `${p.name} (${p.path})` : p.name, String(i), false, i === 0)));
    document.getElementById('urdf-pose-label').hidden = !this.poses.length;
  }

  showTip() {
    this.tip.closest('label').hidden = this.whole.value !== 'chain';
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

// The URDFs among files given together: .urdf files (else .xml ones), those nearest the
// top of the folder first, then by name.
function urdfFiles(files) {
  for (const pattern of [URDF_NAME, XML_NAME]) {
    const candidates = files.filter((f) => pattern.test(f.path));
    candidates.sort((a, b) => depth(a.path) - depth(b.path) || a.path.localeCompare(b.path));
    if (candidates.length) return candidates;
  }
  return [];
}

function depth(path) {
  return path.split('/').length;
}
