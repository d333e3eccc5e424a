// Tick labels of the plots' axes, precise enough to tell every tick apart at any scale:
// uPlot's default keeps at most three decimals, and a pitch axis spanning 0.0180 to 0.0183
// read "0.018" twice.
const MAX_DIGITS = 12;
// Above this many decimals, labels are written in exponent notation ("1.25e-7").
const MAX_FIXED_DECIMALS = 5;
// A label may differ from its tick by this share of the tick spacing.
const LABEL_TOLERANCE = 1e-3;

function exact(values, increment, format) {
  const labels = values.map(format);
  const close = values.every((v, i) => Math.abs(Number(labels[i]) - v) <= LABEL_TOLERANCE * increment);
  return close && new Set(labels).size === labels.length ? labels : null;
}

/** "-0" and "-0.00" read as 0. */
function withoutNegativeZero(label) {
  return Number(label) === 0 ? label.replace(/^-/, '') : label;
}

/**
 * Labels of the ticks `values` (null ones, which uPlot leaves out, stay empty), `increment`
 * apart: the fewest decimals that write each tick to a thousandth of the spacing, and two
 * ticks never the same label.
 */
export function tickLabels(values, increment) {
  const shown = values.filter((v) => v !== null && Number.isFinite(v));
  const spacing = increment > 0 ? increment : 1;
  let labels = null;
  for (let decimals = 0; decimals <= MAX_FIXED_DECIMALS && !labels; decimals++) {
    labels = exact(shown, spacing, (v) => withoutNegativeZero(v.toFixed(decimals)));
  }
  for (let digits = 0; digits <= MAX_DIGITS && !labels; digits++) {
    labels = exact(shown, spacing, (v) => (v === 0 ? '0' : v.toExponential(digits)));
  }
  labels ??= shown.map((v) => String(v));
  let next = 0;
  return values.map((v) => (v !== null && Number.isFinite(v) ? labels[next++] : ''));
}
