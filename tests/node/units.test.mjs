// The unit rule of the JS API (docs/api.md, "Units in the JS API"): every numeric
// field of the TypeScript shapes in pkg/mtmotion.d.ts states its unit,
// either by a unit suffix on its name (gUm, centreXMm, spanDeg, angleRad,
// servoMismatchMs, scaleMismatchPpm, totalReductionPercent, …) or by a doc
// comment that starts with the unit in brackets (`/** [mm] … */`,
// `/** [mm/min] */`, `/** [mm or rad] */`); dimensionless numbers, counts
// and indices say `[-]`. A bracketed unit on a field whose type is an
// inline object applies to the numeric members inside it
// (`/** [mm] */ offset: { z: number; x: number }`).
//
// Numeric means: number, bigint, a typed array, or an alias of them
// (AxisValues), alone or in arrays, tuples, records or unions. Function
// parameters are not fields: their units are in the functions' doc
// comments (each binding's `# Units`). wasm-bindgen's own InitInput /
// InitOutput declarations (the raw wasm exports) are not part of the API.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync, existsSync } from 'node:fs';

const DTS = new URL('../../pkg/mtmotion.d.ts', import.meta.url);

/** A camelCase name that ends in a unit: …Mm, …Um, …Deg, …Rad, …Urad, …Mrad, …S, …Ms, …Us, …Hz, …Ppm, …Percent. */
const UNIT_SUFFIX = /[A-Za-z0-9](Mm|Um|Deg|Rad|Urad|Mrad|S|Ms|Us|Hz|Ppm|Percent)$/;
/** Names that are a unit themselves. */
const UNIT_NAMES = new Set(['seconds', 'milliseconds', 'degrees', 'radians']);
/** A doc comment that starts with the unit in brackets. */
const UNIT_COMMENT = /^\s*\[([^\]\n]+)\]/;
const NUMERIC = /\b(number|bigint|Float64Array|Float32Array|Int8Array|Int16Array|Int32Array|Uint8Array|Uint16Array|Uint32Array|BigInt64Array|BigUint64Array)\b/;

/** Tokens of a .d.ts: doc comments, identifiers, strings, punctuation (other comments dropped). */
function tokenize(text) {
  const tokens = [];
  const re = /(\/\*\*[\s\S]*?\*\/)|(\/\*[\s\S]*?\*\/)|(\/\/[^\n]*)|('(?:\\.|[^'\\])*'|"(?:\\.|[^"\\])*"|`(?:\\.|[^`\\])*`)|([A-Za-z_$][\w$]*)|(=>)|(\S)/g;
  let m;
  while ((m = re.exec(text))) {
    const line = text.slice(0, m.index).split('\n').length;
    if (m[1]) tokens.push({ kind: 'doc', text: m[1].slice(3, -2).replace(/^\s*\*\s?/gm, '').trim(), line });
    else if (m[2] || m[3]) continue;
    else if (m[4]) tokens.push({ kind: 'str', text: m[4], line });
    else if (m[5]) tokens.push({ kind: 'id', text: m[5], line });
    else tokens.push({ kind: 'punct', text: m[6] || m[7], line });
  }
  return tokens;
}

const OPEN = { '{': '}', '(': ')', '[': ']', '<': '>' };

/** Index of the token that closes the bracket opened at `i`. */
function closing(tokens, i) {
  const open = tokens[i].text;
  let depth = 0;
  for (let k = i; k < tokens.length; k++) {
    const t = tokens[k].text;
    if (t === open) depth++;
    else if (t === OPEN[open] && tokens[k - 1]?.text !== '=' && --depth === 0) return k;
  }
  return tokens.length - 1;
}

/** The member type tokens from `i` to the next `;`, `,` or closing bracket at depth 0. */
function typeEnd(tokens, i) {
  let depth = 0;
  for (let k = i; k < tokens.length; k++) {
    const t = tokens[k].text;
    if (tokens[k].kind !== 'punct') continue;
    if (t === '=>') continue;
    if (t in OPEN) depth++;
    else if (Object.values(OPEN).includes(t)) {
      if (depth === 0) return k;
      depth--;
    } else if ((t === ';' || t === ',') && depth === 0) return k;
  }
  return tokens.length;
}

/** Type text with the inside of every `{…}` removed (nested literals are checked on their own). */
function shallow(tokens, from, to) {
  let out = '';
  for (let k = from; k < to; k++) {
    if (tokens[k].text === '{') {
      out += '{}';
      k = closing(tokens, k);
    } else out += `${tokens[k].text} `;
  }
  return out;
}

/**
 * Every numeric field of every interface and type literal in `text` without
 * a unit: [{ path, line }]. Also returns how many numeric fields were seen.
 */
export function fieldsWithoutUnit(text) {
  const cut = text.search(/export type InitInput|export interface InitOutput/);
  const tokens = tokenize(cut >= 0 ? text.slice(0, cut) : text);
  // Aliases of numeric types count as numeric (export type AxisValues = number[] | …).
  const numericAliases = new Set();
  for (let i = 0; i < tokens.length; i++) {
    if (tokens[i].text === 'type' && tokens[i + 1]?.kind === 'id' && tokens[i + 2]?.text === '=') {
      const end = typeEnd(tokens, i + 3);
      if (NUMERIC.test(shallow(tokens, i + 3, end))) numericAliases.add(tokens[i + 1].text);
    }
  }
  const isNumeric = (type) => NUMERIC.test(type) || [...numericAliases].some((a) => new RegExp(`\\b${a}\\b`).test(type));
  const missing = [];
  let seen = 0;

  // Members of the literal whose `{` is at `open`.
  function members(open, path, inherited) {
    const close = closing(tokens, open);
    let doc = null;
    let i = open + 1;
    while (i < close) {
      const t = tokens[i];
      if (t.kind === 'doc') {
        doc = t.text;
        i++;
        continue;
      }
      if (t.text === 'readonly') {
        i++;
        continue;
      }
      const optional = tokens[i + 1]?.text === '?';
      const colon = i + (optional ? 2 : 1);
      if (t.kind === 'id' && tokens[colon]?.text === ':') {
        const end = Math.min(typeEnd(tokens, colon + 1), close);
        const type = shallow(tokens, colon + 1, end);
        const unit = doc && UNIT_COMMENT.test(doc) ? doc.match(UNIT_COMMENT)[1] : null;
        const fieldPath = `${path}.${t.text}`;
        if (isNumeric(type) && !/=>/.test(type)) {
          seen++;
          if (!unit && !inherited && !UNIT_SUFFIX.test(t.text) && !UNIT_NAMES.has(t.text)) missing.push({ path: fieldPath, line: t.line, type: type.trim() });
        }
        for (let k = colon + 1; k < end; k++) {
          if (tokens[k].text === '{') {
            members(k, fieldPath, unit || inherited);
            k = closing(tokens, k);
          }
        }
        i = end + 1;
      } else if (t.text === '{') {
        members(i, path, inherited);
        i = closing(tokens, i) + 1;
      } else if (t.text in OPEN) {
        i = closing(tokens, i) + 1; // index signature, method parameters
      } else i++;
      doc = null;
    }
  }

  for (let i = 0; i < tokens.length; i++) {
    if (tokens[i].text !== '{') continue;
    // Name the literal after its interface, alias or function.
    let name = '?';
    for (let k = i - 1; k >= 0 && k > i - 40; k--) {
      const prev = tokens[k].text;
      if ((prev === 'interface' || prev === 'type' || prev === 'function' || prev === 'class') && tokens[k + 1]?.kind === 'id') {
        name = tokens[k + 1].text;
        break;
      }
    }
    members(i, name, null);
    i = closing(tokens, i);
  }
  return { missing, seen };
}

test('the rule catches a bare numeric field and accepts suffixes, [unit] comments and inherited units', () => {
  const sample = `
export interface Good { gUm: number; spanDeg: number; /** [mm] bar */ radius: number; /** [-] */ count: number; seconds: number;
  /** [mm] */ offset: { z: number; x: number }; name: string; flag: boolean; nested: { /** [s] */ t: number }[] }
export interface Bad { errorZ: number; /** mm, no brackets */ r: number; spectrum: Float64Array | number[]; limits?: Record<string, [number, number]>;
  offset: { z: number }; q?: AxisValues }
export type AxisValues = number[] | Partial<Record<'x', number>>;
export type Motion = { type: 'arc'; sweep: number } | { type: 'dwell'; seconds: number };
export function f(a: number): { position: Float64Array };
export type InitInput = RequestInfo;
export interface InitOutput { readonly memory: WebAssembly.Memory; readonly f: (a: number) => number }
`;
  const { missing, seen } = fieldsWithoutUnit(sample);
  assert.deepEqual(
    missing.map((m) => m.path),
    ['Bad.errorZ', 'Bad.r', 'Bad.spectrum', 'Bad.limits', 'Bad.offset.z', 'Bad.q', 'Motion.sweep', 'f.position'],
  );
  assert.equal(seen, 17);
});

test('every numeric field of pkg/mtmotion.d.ts states its unit', { skip: !existsSync(DTS) && 'pkg/ not built (./scripts/build)' }, () => {
  const { missing, seen } = fieldsWithoutUnit(readFileSync(DTS, 'utf8'));
  assert.ok(seen > 200, `expected the API's numeric fields, found only ${seen}`);
  assert.deepEqual(
    missing.map((m) => `${m.path} (line ${m.line}: ${m.type})`),
    [],
    'numeric fields without a unit suffix or a /** [unit] */ comment',
  );
});
