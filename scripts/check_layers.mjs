// Checks the core's layers (core/CMakeLists.txt names them, the layers each sees and the
// public headers of each) on the source text:
//   - a file in core/src/LAYER/ includes only headers of its own layer and of the layers
//     below it, public (core/include/achd) or private (their folders);
//   - a public header includes only public headers of its layer and the layers below;
//   - every public header and every folder of core/src belongs to a layer;
//   - no folder of core/src holds more than 15 files, no file more than 500 lines.
// The build enforces the private includes too (each layer is compiled seeing only its
// folders); the public headers share one folder, so only this check sees theirs.
//
//   node scripts/check_layers.mjs [ROOT]   prints each violation; exit 1 if any
import { readdirSync, readFileSync, statSync } from 'node:fs';
import { join, relative, resolve } from 'node:path';
import { pathToFileURL } from 'node:url';

export const kMaxFilesPerFolder = 15;
export const kMaxLines = 500;

// The layers as core/CMakeLists.txt sets them: { order, below: {layer: [..]}, extra:
// {layer: [folders]}, publicHeaders: {header: layer} }.
export function readLayers(cmakeText) {
  const sets = {};
  for (const m of cmakeText.matchAll(/^set\((ACHD_[A-Za-z_]+)((?:\s+[^)]*)?)\)/gm))
    sets[m[1]] = m[2].trim().replace(/"/g, '').split(/\s+/).filter(Boolean);
  const order = sets.ACHD_LAYERS ?? [];
  const below = {};
  const extra = {};
  const publicHeaders = {};
  for (const layer of order) {
    below[layer] = sets[`ACHD_LAYER_BELOW_${layer}`] ?? [];
    extra[layer] = sets[`ACHD_LAYER_EXTRA_${layer}`] ?? [];
    for (const h of sets[`ACHD_PUBLIC_${layer}`] ?? []) publicHeaders[h] = layer;
  }
  for (const h of sets.ACHD_PUBLIC_umbrella ?? []) publicHeaders[h] = 'umbrella';
  return { order, below, extra, publicHeaders };
}

function filesUnder(dir) {
  const out = [];
  for (const e of readdirSync(dir, { withFileTypes: true })) {
    const p = join(dir, e.name);
    if (e.isDirectory()) out.push(...filesUnder(p));
    else out.push(p);
  }
  return out;
}

function includes(text) {
  return [...text.matchAll(/^\s*#\s*include\s+"([^"]+)"/gm)].map((m) => m[1]);
}

// Every violation in the tree at `root`, as "path: what is wrong".
export function checkLayers(root) {
  const problems = [];
  const { order, below, extra, publicHeaders } = readLayers(readFileSync(join(root, 'core/CMakeLists.txt'), 'utf8'));
  if (order.length === 0) return ['core/CMakeLists.txt: no ACHD_LAYERS'];
  const src = join(root, 'core/src');
  const pub = join(root, 'core/include/achd');
  const sees = (layer) => new Set([layer, ...below[layer]]);
  const publicLayerSees = (layer) => (layer === 'umbrella' ? new Set(order) : sees(layer));

  // Which layer owns each folder of core/src (its own folder and its extra folders).
  const folderLayer = {};
  for (const layer of order) {
    folderLayer[`core/src/${layer}`] = layer;
    for (const x of extra[layer]) folderLayer[x.startsWith('core/') ? x : `core/${x}`] = layer;
  }
  // Private headers by base name: the layer whose folder holds each.
  const privateLayer = {};
  const sources = filesUnder(src);
  const folders = new Map();
  for (const file of sources) {
    const rel = relative(root, file);
    const folder = rel.slice(0, rel.lastIndexOf('/'));
    folders.set(folder, (folders.get(folder) ?? 0) + 1);
    const layer = folderLayer[folder];
    if (!layer) {
      problems.push(`${rel}: its folder ${folder} is not a layer of core/CMakeLists.txt`);
      continue;
    }
    const name = rel.slice(rel.lastIndexOf('/') + 1);
    if (name.endsWith('.hpp')) (privateLayer[name] ??= []).push(layer);
  }
  for (const [folder, count] of folders)
    if (count > kMaxFilesPerFolder) problems.push(`${folder}: ${count} files, more than ${kMaxFilesPerFolder}`);

  for (const file of sources) {
    const rel = relative(root, file);
    const text = readFileSync(file, 'utf8');
    const lines = text.split('\n').length - (text.endsWith('\n') ? 1 : 0);
    if (lines > kMaxLines) problems.push(`${rel}: ${lines} lines, more than ${kMaxLines}`);
    const layer = folderLayer[rel.slice(0, rel.lastIndexOf('/'))];
    if (!layer) continue;
    const visible = sees(layer);
    for (const inc of includes(text)) {
      if (inc.startsWith('achd/')) {
        const owner = publicHeaders[inc.slice(5)];
        if (!owner) problems.push(`${rel}: includes ${inc}, a public header of no layer`);
        else if (!visible.has(owner))
          problems.push(`${rel}: includes ${inc} of layer ${owner}, above its layer ${layer}`);
        continue;
      }
      const owners = privateLayer[inc];
      if (!owners) continue;  // a system or third-party header
      if (!owners.some((o) => visible.has(o)))
        problems.push(`${rel}: includes ${inc} of layer ${owners.join(', ')}, above its layer ${layer}`);
    }
  }

  for (const name of readdirSync(pub)) {
    const owner = publicHeaders[name];
    if (!owner) {
      problems.push(`core/include/achd/${name}: a public header of no layer (ACHD_PUBLIC_... in core/CMakeLists.txt)`);
      continue;
    }
    const visible = publicLayerSees(owner);
    for (const inc of includes(readFileSync(join(pub, name), 'utf8'))) {
      if (!inc.startsWith('achd/')) {
        problems.push(`core/include/achd/${name}: includes "${inc}", which is not a public header`);
        continue;
      }
      const other = publicHeaders[inc.slice(5)];
      if (other && other !== 'umbrella' && !visible.has(other))
        problems.push(`core/include/achd/${name}: includes ${inc} of layer ${other}, above its layer ${owner}`);
    }
  }
  return problems;
}

if (import.meta.url === pathToFileURL(resolve(process.argv[1] ?? '')).href) {
  const root = resolve(process.argv[2] ?? new URL('..', import.meta.url).pathname);
  if (!statSync(join(root, 'core/src')).isDirectory()) throw new Error(`${root}: no core/src`);
  const problems = checkLayers(root);
  for (const p of problems) console.error(p);
  process.exit(problems.length ? 1 : 0);
}
