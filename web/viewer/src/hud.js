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

export function createHud(root) {
  const title = element('div', 'hud-title', 'Upkie viewer');
  const table = element('dl', 'hud-values');
  const cells = ROWS.map(([label]) => {
    const value = element('dd', '', '–');
    table.append(element('dt', '', label), value);
    return value;
  });
  const status = element('div', 'hud-status', 'loading…');
  const error = element('div', 'hud-error');
  error.hidden = true;
  root.append(title, table, status, error);

  return {
    setTitle(text) {
      title.textContent = text;
    },
    /** Shows a frame given as {name: value}. */
    show(frame) {
      ROWS.forEach(([, format], i) => { cells[i].textContent = format(frame); });
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
