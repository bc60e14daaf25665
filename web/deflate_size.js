// The number of bytes a deflate-raw stream (RFC 1951) expands to, counted by reading its
// Huffman codes without writing a single output byte: the work grows with the compressed
// size, not with the expanded one, so a link of a few hundred KB that would expand to
// gigabytes is measured in milliseconds (web/urdf_share.js refuses it before the
// browser's DecompressionStream spends seconds producing the first 64 MiB).

const LENGTH_BASE = [3, 4, 5, 6, 7, 8, 9, 10, 11, 13, 15, 17, 19, 23, 27, 31, 35, 43, 51, 59, 67, 83, 99, 115,
  131, 163, 195, 227, 258];
const LENGTH_EXTRA = [0, 0, 0, 0, 0, 0, 0, 0, 1, 1, 1, 1, 2, 2, 2, 2, 3, 3, 3, 3, 4, 4, 4, 4, 5, 5, 5, 5, 0];
const DISTANCE_EXTRA = [0, 0, 0, 0, 1, 1, 2, 2, 3, 3, 4, 4, 5, 5, 6, 6, 7, 7, 8, 8, 9, 9, 10, 10, 11, 11, 12, 12,
  13, 13];
// The order the code lengths of the code-length alphabet come in (RFC 1951, 3.2.7).
const CODE_LENGTH_ORDER = [16, 17, 18, 0, 8, 7, 9, 6, 10, 5, 11, 4, 12, 3, 13, 2, 14, 1, 15];

class Bits {
  constructor(bytes) {
    this.bytes = bytes;
    this.at = 0;
    this.word = 0;  // bits not yet used of the current byte, lowest first
    this.count = 0;
  }

  bit() {
    if (this.count === 0) {
      if (this.at >= this.bytes.length) throw new Error('the stream ends early');
      this.word = this.bytes[this.at++];
      this.count = 8;
    }
    const b = this.word & 1;
    this.word >>>= 1;
    this.count--;
    return b;
  }

  bits(n) {
    let v = 0;
    for (let i = 0; i < n; i++) v |= this.bit() << i;
    return v;
  }

  // To the next byte boundary (a stored block's header).
  align() {
    this.count = 0;
  }
}

// A canonical Huffman code from its code lengths: counts[len] codes of each length and
// the symbols in code order, decoded a bit at a time.
function huffman(lengths) {
  const counts = new Uint16Array(16);
  for (const l of lengths) counts[l]++;
  counts[0] = 0;
  const offsets = new Uint16Array(16);
  for (let l = 1; l < 15; l++) offsets[l + 1] = offsets[l] + counts[l];
  const symbols = new Uint16Array(lengths.length);
  lengths.forEach((l, symbol) => {
    if (l) symbols[offsets[l]++] = symbol;
  });
  return { counts, symbols };
}

function decode(bits, code) {
  let first = 0;  // the first code of the current length
  let index = 0;  // the index in symbols of that code
  for (let len = 1; len <= 15; len++) {
    first = 2 * first + bits.bit();
    const n = code.counts[len];
    if (first < n) return code.symbols[index + first];
    index += n;
    first -= n;
  }
  throw new Error('an invalid Huffman code');
}

const FIXED_LITERALS = huffman(Array.from({ length: 288 }, (_, s) => (s < 144 ? 8 : s < 256 ? 9 : s < 280 ? 7 : 8)));
const FIXED_DISTANCES = huffman(new Array(30).fill(5));

function dynamicCodes(bits) {
  const literals = bits.bits(5) + 257;
  const distances = bits.bits(5) + 1;
  const codeLengthCount = bits.bits(4) + 4;
  const codeLengths = new Array(19).fill(0);
  for (let i = 0; i < codeLengthCount; i++) codeLengths[CODE_LENGTH_ORDER[i]] = bits.bits(3);
  const lengthCode = huffman(codeLengths);
  const lengths = [];
  while (lengths.length < literals + distances) {
    const symbol = decode(bits, lengthCode);
    if (symbol < 16) {
      lengths.push(symbol);
    } else {
      const [value, repeat] = symbol === 16 ? [lengths.at(-1), bits.bits(2) + 3]
        : symbol === 17 ? [0, bits.bits(3) + 3] : [0, bits.bits(7) + 11];
      if (value === undefined) throw new Error('a repeated code length with none before it');
      for (let i = 0; i < repeat; i++) lengths.push(value);
    }
  }
  if (lengths.length !== literals + distances) throw new Error('code lengths overrun');
  return [huffman(lengths.slice(0, literals)), huffman(lengths.slice(literals))];
}

// The expanded size of the deflate-raw `bytes`, or the first count past `limit` (counting
// stops there). Throws on a stream that is not valid deflate as far as it is read.
export function inflatedSize(bytes, limit = Infinity) {
  const bits = new Bits(bytes);
  let total = 0;
  for (let last = 0; !last;) {
    last = bits.bit();
    const type = bits.bits(2);
    if (type === 0) {
      bits.align();
      if (bits.at + 4 > bytes.length) throw new Error('the stream ends early');
      const length = bytes[bits.at] | (bytes[bits.at + 1] << 8);
      bits.at += 4 + length;
      if (bits.at > bytes.length) throw new Error('the stream ends early');
      total += length;
    } else if (type === 1 || type === 2) {
      const [literals, distances] = type === 1 ? [FIXED_LITERALS, FIXED_DISTANCES] : dynamicCodes(bits);
      for (;;) {
        const symbol = decode(bits, literals);
        if (symbol < 256) {
          total++;
        } else if (symbol === 256) {
          break;
        } else {
          const k = symbol - 257;
          if (k >= 29) throw new Error('an invalid length code');
          total += LENGTH_BASE[k] + bits.bits(LENGTH_EXTRA[k]);
          const d = decode(bits, distances);
          if (d >= 30) throw new Error('an invalid distance code');
          bits.bits(DISTANCE_EXTRA[d]);
        }
        if (total > limit) return total;
      }
    } else {
      throw new Error('a block of the reserved type 3');
    }
    if (total > limit) return total;
  }
  return total;
}
