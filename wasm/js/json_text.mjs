// The bridge of case-shaped inputs to C++: a JS value written as JSON text, which the
// module's C++ side parses with the CLI's case parser (wasm/src/case_api.cpp,
// tools/case_json.cpp). JS knows nothing of a case's fields here: their forms, checks and
// messages are C++'s.
//
// What JSON would silently change is not written as it is. Every value JSON cannot hold
// (undefined, NaN, +-Infinity, a BigInt, a symbol, a function, a Map, a Set, a DataView,
// an ArrayBuffer, a class instance, a getter, a value that contains itself, one nested
// deeper than any input) is written as a string the C++ side marks as that value
// (tools/foreign_values.hpp), so that the case parser refuses it in its own words, which
// name the field and the index, and adds what it was (", got a Map"; "q[3] is not
// finite"). -0 keeps its sign. A typed array (not a BigInt one) is the array of its
// numbers.
//
// Every input is read once (the case parser sees that one reading): an array's length
// and each element one time, a typed array's elements straight from its memory, an
// object's own enumerable string-keyed properties one time each, so a Proxy or an object
// whose answers change between reads cannot make the text disagree with itself. A getter
// is not called: it is refused (its value could differ between reads, and it would run
// the caller's code in the middle of a call).

import { ACHD_MAX_INPUT_LENGTH, ACHD_TYPED_ARRAYS, achdDescribe, achdIsPlainObject } from './validation.mjs';

// Deeper than any input (a constraint block's alpha column is 4 levels down).
export const ACHD_MAX_INPUT_DEPTH = 32;

const ACHD_FOREIGN_PREFIX = '\u0000achd:';

// A value JSON cannot hold, as the string the C++ side marks as `what` it was.
function achdForeign(what) {
  return JSON.stringify(ACHD_FOREIGN_PREFIX + what);
}

function achdNumberText(x) {
  if (Number.isNaN(x)) return achdForeign('NaN');
  if (x === Infinity) return achdForeign('Infinity');
  if (x === -Infinity) return achdForeign('-Infinity');
  // JSON's -0 reads back as the integer 0: the sign is kept by a fraction.
  if (x === 0 && 1 / x < 0) return '-0.0';
  return String(x);  // the shortest text that reads back as x
}

// A property read once: its value, or the mark of a getter.
function achdOwnValue(d) {
  return 'value' in d ? { value: d.value } : { text: achdForeign('a getter (give plain values)') };
}

function achdWrite(value, open, depth) {
  switch (typeof value) {
    case 'number': return achdNumberText(value);
    case 'string': return JSON.stringify(value);
    case 'boolean': return value ? 'true' : 'false';
    case 'undefined': return achdForeign('undefined');
    case 'bigint': return achdForeign(`${String(value)}n (a BigInt)`);
    case 'symbol': return achdForeign('a symbol');
    case 'function': return achdForeign('a function');
    default: break;
  }
  if (value === null) return 'null';
  if (open.has(value)) return achdForeign('a value that contains itself');
  if (depth >= ACHD_MAX_INPUT_DEPTH) return achdForeign(`a value nested more than ${ACHD_MAX_INPUT_DEPTH} deep`);
  if (ArrayBuffer.isView(value) && ACHD_TYPED_ARRAYS.some((T) => value instanceof T)) {
    if (value.length > ACHD_MAX_INPUT_LENGTH)
      return achdForeign(`an array of ${value.length} numbers (more than the ${ACHD_MAX_INPUT_LENGTH} an input may have)`);
    return `[${Array.from(new Float64Array(value), achdNumberText).join(',')}]`;
  }
  const parts = [];
  open.add(value);
  try {
    if (Array.isArray(value)) {
      const lengthProperty = Object.getOwnPropertyDescriptor(value, 'length');
      const n = lengthProperty === undefined ? undefined : lengthProperty.value;
      if (!Number.isSafeInteger(n) || n < 0) return achdForeign('an array without a length');
      if (n > ACHD_MAX_INPUT_LENGTH)
        return achdForeign(`an array of ${n} values (more than the ${ACHD_MAX_INPUT_LENGTH} an input may have)`);
      for (let i = 0; i < n; ++i) {
        const d = Object.getOwnPropertyDescriptor(value, i);
        const v = d === undefined ? { value: undefined } : achdOwnValue(d);
        parts.push('text' in v ? v.text : achdWrite(v.value, open, depth + 1));
      }
      return `[${parts.join(',')}]`;
    }
    if (!achdIsPlainObject(value)) return achdForeign(achdDescribe(value));
    for (const key of Reflect.ownKeys(value)) {
      if (typeof key !== 'string') continue;  // symbol keys name nothing
      const d = Object.getOwnPropertyDescriptor(value, key);
      if (d === undefined || !d.enumerable) continue;
      const v = achdOwnValue(d);
      parts.push(`${JSON.stringify(key)}:${'text' in v ? v.text : achdWrite(v.value, open, depth + 1)}`);
    }
    return `{${parts.join(',')}}`;
  } finally {
    open.delete(value);
  }
}

// `value` as the JSON text the C++ side reads (see the top).
export function achdJsonText(value) {
  return achdWrite(value, new Set(), 0);
}
