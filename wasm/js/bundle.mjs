// Joins the ES modules of the JS wrapper into the one script Emscripten's --post-js takes
// (it runs inside the module factory, where modules cannot be imported): each module's
// `import { ... } from './x.mjs';` lines are dropped and `export ` is taken off its
// declarations; every top-level name is unique across the files (achd prefix or class
// name), so they share the factory's scope. Usage: node bundle.mjs OUT IN...
import { readFileSync, writeFileSync } from 'node:fs';
import { basename } from 'node:path';

const [out, ...inputs] = process.argv.slice(2);
const parts = inputs.map((file) => {
  const text = readFileSync(file, 'utf8')
    .replace(/^import \{[^}]*\} from '\.\/[\w]+\.mjs';\n/gm, '')
    .replace(/^export (?=(function|class|const|let) )/gm, '');
  if (/^\s*(import|export)\b/m.test(text)) throw new Error(`${file}: an import or export the bundle cannot take`);
  return `// ---- wasm/js/${basename(file)}\n${text}`;
});
writeFileSync(out, parts.join('\n'));
