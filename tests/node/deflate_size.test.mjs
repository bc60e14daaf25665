// web/deflate_size.js counts what a deflate-raw stream expands to without expanding it:
// the count is exact for every URDF of robots/ at every zlib level and strategy (stored,
// fixed and dynamic Huffman blocks) and for 200 random texts; a 200 MB bomb is measured
// past the 64 MiB limit in well under a second; a damaged stream throws.
import assert from 'node:assert/strict';
import { readFileSync, readdirSync } from 'node:fs';
import { test } from 'node:test';
import { constants, deflateRawSync } from 'node:zlib';

import { inflatedSize } from '../../web/deflate_size.js';

const ROBOTS = new URL('../../robots/', import.meta.url);

test('the count is the expanded size for every kind of block', () => {
  const texts = readdirSync(ROBOTS).filter((f) => f.endsWith('.urdf')).map((f) => readFileSync(new URL(f, ROBOTS)));
  let seed = 1;
  const random = () => ((seed = (seed * 1103515245 + 12345) % 2147483648) / 2147483648);
  for (let i = 0; i < 200; i++) {
    const b = Buffer.alloc(Math.floor(random() * 100000));
    for (let j = 0; j < b.length; j++) b[j] = random() < 0.7 ? 65 + (j % 7) : Math.floor(random() * 256);
    texts.push(b);
  }
  texts.push(Buffer.alloc(0));
  const options = [{ level: 0 }, { level: 1 }, { level: 6 }, { level: 9 }, { strategy: constants.Z_FIXED },
    { strategy: constants.Z_HUFFMAN_ONLY }, { strategy: constants.Z_RLE }];
  for (const text of texts) {
    for (const o of options) assert.equal(inflatedSize(deflateRawSync(text, o)), text.length, JSON.stringify(o));
  }
});

test('a bomb is measured past the limit at once', () => {
  const limit = 64 * 1024 * 1024;
  const bomb = deflateRawSync(Buffer.alloc(200 * 1024 * 1024, 0x20), { level: 9 });
  const start = performance.now();
  const size = inflatedSize(bomb, limit);
  const ms = performance.now() - start;
  assert.ok(size > limit && size < limit + 300, `${size}`);
  assert.ok(ms < 500, `${ms} ms`);
  assert.equal(inflatedSize(bomb), 200 * 1024 * 1024);
});

test('a damaged stream throws', () => {
  const packed = deflateRawSync(readFileSync(new URL('ur5.urdf', ROBOTS)));
  assert.throws(() => inflatedSize(packed.subarray(0, packed.length >> 1)), /ends early/);
  assert.throws(() => inflatedSize(Uint8Array.of(0x07)), /reserved type 3/);
});
