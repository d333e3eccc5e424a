// The text overlay of the scene: title, the drawn frame's numbers, a status line and the
// last error, if any.
const ROWS = [
  ['Episode', (f) => String(f.episode)],
  ['Step', (f) => String(f.step)],
  ['Time', (f) => `${f.time.toFixed(3)} s`],
  ['Return', (f) => f.return.toFixed(2)],
  ['Pitch', (f) => `${f.pitch.toFixed(3)} rad`],
  ['Ground position', (f) => `${f.ground_position.toFixed(3)} m`],
];

function element(tag, className, text = '') {
  const node = document.createElement(tag);
  node.className = className;
  node.textContent = text;
  return node;
}

/**
 * One row per chart of the session (e.g. "Forward velocity": "command 0.40 · measured 0.38"),
 * its values looked up by field name.
 */
function chartRows(charts) {
  return charts.map(({ title, series }) => [
    title.replace(/ \[.*\]$/, ''),
    (f) => series.map(({ label, field }) => `${label} ${f[field].toFixed(2)}`).join(' · '),
  ]);
}

export function createHud(root) {
  const rows = [];
  const cells = [];
  const title = element('div', 'hud-title', 'Upkie viewer');
  const table = element('dl', 'hud-values');
  function addRows(added) {
    for (const row of added) {
      const value = element('dd', '', '–');
      table.append(element('dt', '', row[0]), value);
      rows.push(row);
      cells.push(value);
    }
  }
  addRows(ROWS);
  const status = element('div', 'hud-status', 'loading…');
  const drive = element('div', 'hud-drive');
  drive.hidden = true;
  const keys = element('dl', 'hud-keys');
  keys.hidden = true;
  const error = element('div', 'hud-error');
  error.hidden = true;
  root.append(title, table, status, drive, keys, error);

  return {
    setTitle(text) {
      title.textContent = text;
    },
    /** Adds a row per chart of the session (command against measured velocity). */
    addCharts(charts) {
      addRows(chartRows(charts));
    },
    /** Shows a frame given as {name: value}. */
    show(frame) {
      rows.forEach(([, format], i) => { cells[i].textContent = format(frame); });
    },
    /** The driving line: role, pause, latency, the last refusal; `kind` as setStatus. */
    setDrive(text, kind) {
      drive.hidden = false;
      drive.textContent = text;
      drive.dataset.kind = kind;
    },
    /** The key legend: [keys, what they do] rows. */
    setKeys(legend) {
      keys.replaceChildren(...legend.flatMap(([key, action]) => [element('dt', '', key), element('dd', '', action)]));
      keys.hidden = false;
    },
    /** `kind` colours the status dot: 'ok', 'idle' or 'bad'. */
    setStatus(text, kind) {
      status.textContent = text;
      status.dataset.kind = kind;
    },
    showError(message) {
      error.textContent = message;
      error.hidden = false;
    },
  };
}
