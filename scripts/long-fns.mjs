#!/usr/bin/env node
// Lists the Rust functions in src/ longer than a limit (default 80 lines,
// the house rule), longest first, and prints their count.
//
//   node scripts/long-fns.mjs            # functions over 80 lines
//   node scripts/long-fns.mjs --max 100  # over 100 lines
//   node scripts/long-fns.mjs --all      # every function with its length
//
// A function's length counts from its `fn` line to its closing brace,
// both included (doc comments and attributes above it are not counted).
// Comments, strings (raw strings too: the TypeScript sections hold braces)
// and character literals are skipped when braces are matched. Functions in
// a `#[cfg(test)]` module are listed with "(test)". Always exits 0: it
// reports, the coordinator decides.
import { readdirSync, readFileSync, statSync } from 'node:fs';
import { join, relative } from 'node:path';
import { fileURLToPath } from 'node:url';

const root = join(fileURLToPath(import.meta.url), '..', '..');
const args = process.argv.slice(2);
const maxAt = args.indexOf('--max');
const MAX = maxAt >= 0 ? Number(args[maxAt + 1]) : 80;
const ALL = args.includes('--all');

function rustFiles(dir) {
  return readdirSync(dir).flatMap((name) => {
    const p = join(dir, name);
    if (statSync(p).isDirectory()) return rustFiles(p);
    return name.endsWith('.rs') ? [p] : [];
  });
}

/**
 * The source with every comment, string and character literal replaced by
 * spaces (newlines kept), so that braces and `fn` can be found by position.
 */
export function blank(src) {
  const out = src.split('');
  const wipe = (from, to) => {
    for (let k = from; k < to; k++) if (out[k] !== '\n') out[k] = ' ';
  };
  let i = 0;
  while (i < src.length) {
    const c = src[i];
    const next = src[i + 1];
    if (c === '/' && next === '/') {
      const end = src.indexOf('\n', i);
      const stop = end < 0 ? src.length : end;
      wipe(i, stop);
      i = stop;
    } else if (c === '/' && next === '*') {
      let depth = 1;
      let k = i + 2;
      while (k < src.length && depth > 0) {
        if (src[k] === '/' && src[k + 1] === '*') (depth++, (k += 2));
        else if (src[k] === '*' && src[k + 1] === '/') (depth--, (k += 2));
        else k++;
      }
      wipe(i, k);
      i = k;
    } else if ((c === 'r' || (c === 'b' && next === 'r')) && /^b?r#*"/.test(src.slice(i, i + 40)) && !/\w/.test(src[i - 1] || '')) {
      const m = /^b?r(#*)"/.exec(src.slice(i, i + 40));
      const close = `"${m[1]}`;
      const end = src.indexOf(close, i + m[0].length);
      const stop = end < 0 ? src.length : end + close.length;
      wipe(i, stop);
      i = stop;
    } else if (c === '"') {
      let k = i + 1;
      while (k < src.length && src[k] !== '"') k += src[k] === '\\' ? 2 : 1;
      wipe(i, k + 1);
      i = k + 1;
    } else if (c === "'") {
      // A character literal ('a', '\n', '\u{1F600}', '{') — not a lifetime ('a).
      const m = /^'(\\u\{[0-9a-fA-F]+\}|\\.|[^\\'\n])'/u.exec(src.slice(i, i + 12));
      if (m) {
        wipe(i, i + m[0].length);
        i += m[0].length;
      } else i++;
    } else i++;
  }
  return out.join('');
}

const FN = /(?:^|[^\w])fn\s+([A-Za-z_]\w*)/g;

/** Every function with a body in `src`: { name, line, lines, test }. */
export function functions(src) {
  const code = blank(src);
  const lineAt = (pos) => code.slice(0, pos).split('\n').length;
  // Where the `#[cfg(test)] mod …` blocks are.
  const testRanges = [];
  for (const m of code.matchAll(/#\[cfg\(test\)\]\s*(?:pub(?:\([^)]*\))?\s+)?mod\s+\w+\s*\{/g)) {
    const open = m.index + m[0].length - 1;
    testRanges.push([open, matchBrace(code, open)]);
  }
  const found = [];
  for (const m of code.matchAll(FN)) {
    const at = m.index + m[0].indexOf('fn');
    // The body starts at the first `{` at nesting depth 0 of the signature;
    // a `;` first means a declaration without a body (trait method).
    let depth = 0;
    let k = at;
    for (; k < code.length; k++) {
      const ch = code[k];
      if (ch === '(' || ch === '[' || ch === '<') depth++;
      else if ((ch === ')' || ch === ']' || (ch === '>' && code[k - 1] !== '-' && code[k - 1] !== '=')) && depth > 0) depth--;
      else if (ch === ';' && depth === 0) break;
      else if (ch === '{' && depth === 0) break;
    }
    if (code[k] !== '{') continue;
    const close = matchBrace(code, k);
    const first = lineAt(at);
    const last = lineAt(close);
    found.push({ name: m[1], line: first, lines: last - first + 1, test: testRanges.some(([a, b]) => at > a && at < b) });
  }
  return found;
}

function matchBrace(code, open) {
  let depth = 0;
  for (let k = open; k < code.length; k++) {
    if (code[k] === '{') depth++;
    else if (code[k] === '}' && --depth === 0) return k;
  }
  return code.length - 1;
}

if (import.meta.url === `file://${process.argv[1]}`) {
  const rows = rustFiles(join(root, 'src')).flatMap((file) =>
    functions(readFileSync(file, 'utf8')).map((f) => ({ ...f, file: relative(root, file) })),
  );
  rows.sort((a, b) => b.lines - a.lines);
  const long = rows.filter((r) => r.lines > MAX);
  for (const r of ALL ? rows : long) console.log(`${String(r.lines).padStart(4)}  ${r.file}:${r.line}  ${r.name}${r.test ? ' (test)' : ''}`);
  const tests = long.filter((r) => r.test).length;
  console.log(`${long.length} functions over ${MAX} lines in src/ (${long.length - tests} outside test modules, ${tests} in them), of ${rows.length}`);
}
