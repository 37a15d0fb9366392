// The layer check of scripts/check-layers.mjs: the real core passes, and a
// planted cycle (kinematics importing machine, which imports kinematics) or
// a planted sideways import fails with a message naming the file.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { cpSync, mkdtempSync, readFileSync, writeFileSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { checkLayers, importsOf } from '../../scripts/check-layers.mjs';

const src = new URL('../../src', import.meta.url).pathname;

test('the core has no upward or sideways import and no cycle', () => {
  assert.deepEqual(checkLayers(src).problems, []);
});

function planted(file, line) {
  const dir = mkdtempSync(join(tmpdir(), 'layers-'));
  cpSync(src, dir, { recursive: true });
  const path = join(dir, file);
  writeFileSync(path, `${line}\n${readFileSync(path, 'utf8')}`);
  try {
    return checkLayers(dir).problems;
  } finally {
    rmSync(dir, { recursive: true, force: true });
  }
}

test('a planted kinematics -> machine import is an upward import and a cycle', () => {
  const problems = planted('kinematics/chain.rs', 'use crate::machine::Machine;');
  assert.ok(problems.some((p) => p.includes('kinematics/chain.rs') && p.includes('upward')), problems.join('\n'));
  assert.ok(problems.some((p) => /import cycle: .*kinematics.*machine|import cycle: .*machine.*kinematics/.test(p)), problems.join('\n'));
});

test('a planted kinematics -> servo import is sideways: drive errors are the drive\'s', () => {
  const problems = planted('kinematics/errors.rs', 'use crate::servo::WormHarmonic;');
  assert.ok(problems.some((p) => p.includes('kinematics/errors.rs') && p.includes('sideways') && p.includes("'servo'")), problems.join('\n'));
});

test('a planted sideways import (compensate -> cone_frustum) fails', () => {
  const problems = planted('compensate/mod.rs', 'use crate::cone_frustum::ConeFrustumConfig;');
  assert.ok(problems.some((p) => p.includes('sideways') && p.includes("'cone_frustum'")), problems.join('\n'));
});

test('imports in comments and in the unit-test module do not count; grouped imports do', () => {
  const text = '//! see [`crate::wasm`]\nuse crate::{servo::Axis, nc};\nfn f() {} // crate::machine\n#[cfg(test)]\nmod tests { use crate::machine; }\n';
  assert.deepEqual([...importsOf(text)].sort(), ['nc', 'servo']);
});

test('an unknown top-level module must be placed in the table', () => {
  const dir = mkdtempSync(join(tmpdir(), 'layers-'));
  cpSync(src, dir, { recursive: true });
  writeFileSync(join(dir, 'mystery.rs'), 'pub fn f() {}\n');
  const { problems } = checkLayers(dir);
  rmSync(dir, { recursive: true, force: true });
  assert.ok(problems.some((p) => p.includes("'mystery' is not in the layer table")), problems.join('\n'));
});
