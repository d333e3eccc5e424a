// Live frames from the server's WebSocket: binary messages of whole little-endian float64
// frame rows (oldest first), text messages of JSON events (the end of the run here; the
// others go to onMessage). Reconnects every 2 s when closed before the run said it ended.
// state.send(text) sends a text message while connected.
import { guard, reportError } from './errors.js';

const RETRY_MS = 2000;
// The frame rate is the frames that arrived in this window, over the window (or over the
// time since the connection opened, when shorter): read when shown, it stays true when the
// server sends frames in batches or the browser delays the page's timers.
const RATE_WINDOW_MS = 2000;
const STATUS_MS = 500;

export function createLiveSource(session, layout, { onFrames, onStatusChange, onMessage = () => {} }) {
  const url = (window.location.protocol === 'https:' ? 'wss://' : 'ws://')
    + window.location.host + session.websocket;
  const state = {
    connected: false,
    framesReceived: 0,
    framesPerSecond: 0,
    endReason: null,
    latest: null,  // {data, offset} of the newest frame row
    send: () => false,  // replaced while connected
  };
  const arrivals = [];  // [time [ms], frame count] of the messages in the rate window
  let connectedAt = 0;

  /** Frames per second over the rate window, at `now` [ms]. */
  function frameRate(now) {
    while (arrivals.length > 0 && arrivals[0][0] <= now - RATE_WINDOW_MS) arrivals.shift();
    const frames = arrivals.reduce((sum, [, count]) => sum + count, 0);
    const span = Math.min(RATE_WINDOW_MS, now - connectedAt);
    return span > 0 ? Math.round((1000 * frames) / span) : 0;
  }

  function status() {
    if (state.endReason !== null) {
      return [`ended: ${state.endReason}${state.connected ? '' : ' (disconnected)'}`, 'idle'];
    }
    if (!state.connected) return ['disconnected', 'bad'];
    state.framesPerSecond = frameRate(performance.now());
    if (state.framesReceived === 0) return ['live: waiting for frames', 'idle'];
    return [`live: ${state.framesPerSecond} frames/s (${state.framesReceived} received)`, 'ok'];
  }

  function onBinary(buffer) {
    const rowBytes = layout.size * Float64Array.BYTES_PER_ELEMENT;
    if (buffer.byteLength === 0 || buffer.byteLength % rowBytes !== 0) {
      throw new Error(`frame message of ${buffer.byteLength} bytes is not whole rows of ${rowBytes}`);
    }
    const data = new Float64Array(buffer);
    const count = data.length / layout.size;
    state.framesReceived += count;
    arrivals.push([performance.now(), count]);
    state.latest = { data, offset: (count - 1) * layout.size };
    onFrames(data, count, state);
  }

  function onText(text) {
    const message = JSON.parse(text);
    if (message.type === 'end') {
      state.endReason = String(message.reason ?? 'run ended');
      onStatusChange(status(), state);
    } else {
      onMessage(message);
    }
  }

  function connect() {
    const socket = new WebSocket(url);
    socket.binaryType = 'arraybuffer';
    socket.onopen = guard('websocket open', () => {
      state.connected = true;
      connectedAt = performance.now();
      state.send = (text) => {
        if (socket.readyState !== WebSocket.OPEN) return false;
        socket.send(text);
        return true;
      };
      state.endReason = null;  // a new connection streams a new run
      onStatusChange(status(), state);
    });
    socket.onmessage = guard('websocket message', (event) => {
      if (typeof event.data === 'string') onText(event.data);
      else onBinary(event.data);
    });
    socket.onclose = guard('websocket close', () => {
      state.connected = false;
      state.send = () => false;
      onStatusChange(status(), state);
      // After an end message the process is gone: retrying would only log failures.
      if (state.endReason === null) setTimeout(guard('websocket reconnect', connect), RETRY_MS);
    });
  }

  setInterval(guard('frame rate', () => {
    if (state.connected) onStatusChange(status(), state);
  }), STATUS_MS);

  try {
    connect();
  } catch (err) {
    reportError(err, 'websocket');
  }
  onStatusChange(status(), state);
  return state;
}
