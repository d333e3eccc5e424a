// Every failure of the viewer ends up in one list that tests read (window.upkieViewer.errors)
// and on the console, so nothing fails silently.
export const errors = [];

export function reportError(err, where) {
  const message = `${where}: ${err && err.message ? err.message : String(err)}`;
  errors.push(message);
  console.error(`upkie viewer: ${message}`, err);
  for (const listener of listeners) listener(message);
}

const listeners = [];

/** Calls `listener(message)` for every error reported from now on. */
export function onError(listener) {
  listeners.push(listener);
}

/** Wraps a callback (event handler, animation frame) so its exceptions are reported. */
export function guard(where, fn) {
  return (...args) => {
    try {
      return fn(...args);
    } catch (err) {
      reportError(err, where);
      return undefined;
    }
  };
}

window.addEventListener('error', (event) => {
  reportError(event.error ?? event.message, 'uncaught');
});
window.addEventListener('unhandledrejection', (event) => {
  reportError(event.reason, 'unhandled rejection');
});
