// The plots' tick labels (src/ticks.js) without a browser: distinct at any scale, no more
// digits than the spacing needs.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { tickLabels } from '../src/ticks.js';

function ticks(low, increment, count) {
  return Array.from({ length: count }, (_, i) => low + i * increment);
}

test('ticks a tenth of a thousandth apart get four decimals, not 0.018 twice', () => {
  assert.deepEqual(tickLabels(ticks(0.0180, 0.0001, 4), 0.0001),
    ['0.0180', '0.0181', '0.0182', '0.0183']);
});

test('whole ticks get no decimals, and zero no sign', () => {
  assert.deepEqual(tickLabels([-10, -5, -0, 5], 5), ['-10', '-5', '0', '5']);
  assert.deepEqual(tickLabels(ticks(-0.2, 0.1, 5), 0.1), ['-0.2', '-0.1', '0.0', '0.1', '0.2']);
});

test('tiny spacings switch to exponent notation and stay distinct', () => {
  const labels = tickLabels(ticks(1e-7, 2.5e-8, 5), 2.5e-8);
  assert.deepEqual(labels, ['1.00e-7', '1.25e-7', '1.50e-7', '1.75e-7', '2.00e-7']);
});

test('zero reads 0 among exponent labels', () => {
  assert.deepEqual(tickLabels([-2.5e-6, 0, 2.5e-6], 2.5e-6), ['-2.5e-6', '0', '2.5e-6']);
});

test('labels are distinct at every scale and offset', () => {
  for (let exponent = -12; exponent <= 6; exponent++) {
    for (const mantissa of [1, 2, 2.5, 5]) {
      const increment = mantissa * 10 ** exponent;
      for (const offset of [0, 0.0183, -7, 12345]) {
        // Spacings below a billionth of the values are not distinct doubles, nor uPlot's.
        if (increment < Math.abs(offset) * 1e-9) continue;
        const values = ticks(Math.round(offset / increment) * increment, increment, 6);
        const labels = tickLabels(values, increment);
        assert.equal(new Set(labels).size, labels.length, `${labels} (spacing ${increment})`);
        labels.forEach((label, i) => assert.ok(
          Math.abs(Number(label) - values[i]) <= 1e-3 * increment, `${label} for ${values[i]}`));
      }
    }
  }
});

test('ticks uPlot leaves out stay empty', () => {
  assert.deepEqual(tickLabels([null, 1, 2], 1), ['', '1', '2']);
});
