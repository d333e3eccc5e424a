// Driving from the page (`upkie-rl drive`): the keyboard (arrows or WASD) and a gamepad (the
// browser's Gamepad API) give a velocity command, sent over the WebSocket when it changes;
// the server says which page drives. Every wire key comes from session.drive.keys.
//
// Keys: up/W forward, down/S backward, left/A turn left, right/D turn right (half the range;
// with Shift the full range), R reset, P pause, B push the robot forward (Shift+B backward);
// with a height command (session.drive.limits.min_height), Q raises and Z lowers the base
// by a tenth of the height range per press (it starts standing, at the top); a click on the
// robot pushes it away from the camera.
// Gamepad (standard mapping): left stick up/down forward velocity, right stick left/right
// yaw rate, Back/Select (button 8) reset, Start (button 9) pause, A/cross (button 0) push,
// D-pad up/down (buttons 12/13) raise/lower the base.
import { guard } from './errors.js';

const KEY_FRACTION = 0.5;  // of the range, without Shift
const TICK_MS = 20;  // gamepad polling and command sending: the agent's 50 Hz
const DEADZONE = 0.1;  // of a stick's travel
const CLICK_SLOP = 5;  // pixels a click may move and still be a click, not an orbit
const BUTTON_RESET = 8;
const BUTTON_PAUSE = 9;
const BUTTON_PUSH = 0;
const BUTTON_RAISE = 12;
const BUTTON_LOWER = 13;
const HEIGHT_STEPS = 10;  // presses from the top of the height range to its bottom
const AXIS_FORWARD = 1;  // left stick, up is -1
const AXIS_YAW = 2;  // right stick, right is +1
// Latencies and refusals the page keeps (the newest), and commands awaiting their "applied":
// a page left open for hours must not grow them without bound.
const MAX_SAMPLES = 256;

const FORWARD_KEYS = { ArrowUp: 1, KeyW: 1, ArrowDown: -1, KeyS: -1 };
const YAW_KEYS = { ArrowLeft: 1, KeyA: 1, ArrowRight: -1, KeyD: -1 };
const HEIGHT_KEYS = { KeyQ: 1, KeyZ: -1 };
// The other keys, by the message they send (once per press).
const COMMAND_KEYS = { KeyR: 'reset', KeyP: 'pause', KeyB: 'push' };

/** How a key code reads on a keyboard: "↑", "W". */
function keyName(code) {
  return { ArrowUp: '↑', ArrowDown: '↓', ArrowLeft: '←', ArrowRight: '→' }[code] ?? code.replace(/^Key/, '');
}

/** The keys of `map` (FORWARD_KEYS, YAW_KEYS or HEIGHT_KEYS) that move with `sign`, as they read. */
function keysOf(map, sign) {
  return Object.keys(map).filter((code) => map[code] === sign).map(keyName).join(' / ');
}

const commandKey = (name) => keyName(Object.keys(COMMAND_KEYS).find((code) => COMMAND_KEYS[code] === name));

/** The page's key legend, [keys, what they do], from the tables the handlers read. */
export const KEY_LEGEND = [
  [keysOf(FORWARD_KEYS, 1), 'forward'],
  [keysOf(FORWARD_KEYS, -1), 'backward'],
  [keysOf(YAW_KEYS, 1), 'turn left'],
  [keysOf(YAW_KEYS, -1), 'turn right'],
  [keysOf(HEIGHT_KEYS, 1), 'raise the base (with a height command)'],
  [keysOf(HEIGHT_KEYS, -1), 'lower the base'],
  ['Shift', `full range (${KEY_FRACTION * 100} % without)`],
  [commandKey('reset'), 'reset'],
  [commandKey('pause'), 'pause'],
  [`${commandKey('push')} / Shift+${commandKey('push')}`, 'push forward / backward'],
  ['click the robot', 'push it away'],
  ['gamepad', 'left stick forward, right stick turn, D-pad up/down height, A push, Start pause, Back reset'],
];

/** Appends `value` to `samples`, forgetting the oldest beyond MAX_SAMPLES. */
function pushBounded(samples, value) {
  samples.push(value);
  if (samples.length > MAX_SAMPLES) samples.splice(0, samples.length - MAX_SAMPLES);
}

function sameFraction(a, b) {
  return a.forward === b.forward && a.yaw === b.yaw && a.height === b.height;
}

function deadzone(value) {
  return Math.abs(value) < DEADZONE ? 0 : value;
}

/** The command of the held keys as fractions of the range, or null when none is held. */
function keyboardFraction(held, shift) {
  let forward = 0;
  let yaw = 0;
  let any = false;
  for (const code of held) {
    if (code in FORWARD_KEYS) { forward += FORWARD_KEYS[code]; any = true; }
    if (code in YAW_KEYS) { yaw += YAW_KEYS[code]; any = true; }
  }
  if (!any) return null;
  const scale = shift ? 1 : KEY_FRACTION;
  return { forward: Math.sign(forward) * scale, yaw: Math.sign(yaw) * scale };
}

/**
 * `send(text)` sends a text message (false when disconnected); `hud` shows the role;
 * `robotYaw()` and `pushTarget(event)` locate the robot for pushes.
 */
export function createDrive(session, { send, hud, robotYaw, pushDirection, canvas }) {
  const K = session.drive.keys;
  const limits = session.drive.limits;
  const hasHeight = typeof limits.min_height === 'number' && typeof limits.max_height === 'number';
  const state = {
    role: null, paused: false, reason: '', refusals: [], sent: 0,
    // Fractions of the ranges, last sent and not refused; height 1 is the top (standing).
    command: { forward: 0, yaw: 0, height: 1 },
    height: 1,  // the height asked by Q/Z or the D-pad, a fraction of the height range
    latencies: [],  // key press (or stick move) to the server's "applied" [ms], the newest
    testGamepad: null,  // a gamepad-like {axes, buttons} that replaces the real ones (tests)
  };
  const held = new Set();
  let shift = false;
  let sequence = 0;
  // The command last sent, refused or not: a page that watches sends each change once, not
  // again at every tick while the other page drives.
  let attempted = { forward: 0, yaw: 0, height: 1 };
  const pressedAt = new Map();  // sequence -> time of the input that caused it, oldest first
  let lastButtons = [];

  function message(type, fields = {}) {
    const sentOk = send(JSON.stringify({ [K.type]: type, ...fields }));
    if (sentOk) state.sent += 1;
    return sentOk;
  }

  function sendCommand(fraction, inputTime) {
    if (sameFraction(fraction, attempted)) return;
    sequence += 1;
    const fields = {
      [K.seq]: sequence,
      [K.forward_velocity]: fraction.forward * limits.max_forward_velocity,
      [K.yaw_rate]: fraction.yaw * limits.max_yaw_rate,
    };
    if (hasHeight) {
      fields[K.height] = limits.min_height + fraction.height * (limits.max_height - limits.min_height);
    }
    const ok = message(K.command, fields);
    if (!ok) return;  // disconnected: tried again at the next tick
    attempted = fraction;
    state.command = fraction;
    pressedAt.set(sequence, inputTime);
    // Refused commands never get their "applied".
    if (pressedAt.size > MAX_SAMPLES) pressedAt.delete(pressedAt.keys().next().value);
  }

  function gamepad() {
    if (state.testGamepad) return state.testGamepad;
    const pads = navigator.getGamepads ? navigator.getGamepads() : [];
    return Array.from(pads).find((pad) => pad && pad.connected) ?? null;
  }

  function pressedEdge(pad, index) {
    const pressed = Boolean(pad.buttons[index]?.pressed);
    return pressed && !lastButtons[index];
  }

  /** The command to send now: held keys first, else the gamepad's sticks; the height asked. */
  function currentFraction(pad) {
    const keys = keyboardFraction(held, shift);
    if (keys) return { ...keys, height: state.height };
    if (!pad) return { forward: 0, yaw: 0, height: state.height };
    return {
      forward: Math.max(-1, Math.min(1, -deadzone(pad.axes[AXIS_FORWARD] ?? 0))),
      yaw: Math.max(-1, Math.min(1, -deadzone(pad.axes[AXIS_YAW] ?? 0))),
      height: state.height,
    };
  }

  /** Raises (direction 1) or lowers (-1) the height asked by a step, within the range. */
  function stepHeight(direction) {
    if (!hasHeight) return;
    const steps = Math.round(state.height * HEIGHT_STEPS) + direction;
    state.height = Math.max(0, Math.min(HEIGHT_STEPS, steps)) / HEIGHT_STEPS;
  }

  function tick() {
    const pad = gamepad();
    if (pad) {
      if (pressedEdge(pad, BUTTON_RESET)) message(K.reset);
      if (pressedEdge(pad, BUTTON_PAUSE)) message(K.pause);
      if (pressedEdge(pad, BUTTON_PUSH)) message(K.push, { [K.heading]: 0 });
      if (pressedEdge(pad, BUTTON_RAISE)) stepHeight(1);
      if (pressedEdge(pad, BUTTON_LOWER)) stepHeight(-1);
      lastButtons = pad.buttons.map((button) => Boolean(button?.pressed));
    }
    sendCommand(currentFraction(pad), performance.now());
  }
  setInterval(guard('drive tick', tick), TICK_MS);

  window.addEventListener('keydown', guard('drive key', (event) => {
    shift = event.shiftKey;
    if (event.code in FORWARD_KEYS || event.code in YAW_KEYS) {
      event.preventDefault();  // arrows would scroll
      held.add(event.code);
      sendCommand(currentFraction(gamepad()), event.timeStamp);
    } else if (event.code in HEIGHT_KEYS) {
      stepHeight(HEIGHT_KEYS[event.code]);  // a held key repeats: the base keeps moving
      sendCommand(currentFraction(gamepad()), event.timeStamp);
    } else if (event.repeat) {
      // held R, P or B: once
    } else if (COMMAND_KEYS[event.code] === 'reset') {
      message(K.reset);
    } else if (COMMAND_KEYS[event.code] === 'pause') {
      message(K.pause);
    } else if (COMMAND_KEYS[event.code] === 'push') {
      message(K.push, { [K.heading]: event.shiftKey ? Math.PI : 0 });
    }
  }));
  window.addEventListener('keyup', guard('drive key', (event) => {
    shift = event.shiftKey;
    held.delete(event.code);
    sendCommand(currentFraction(gamepad()), event.timeStamp);
  }));
  // A page that loses focus no longer sees its keys come up: it stops.
  window.addEventListener('blur', guard('drive blur', () => {
    held.clear();
    sendCommand(currentFraction(gamepad()), performance.now());
  }));

  // A click (not an orbit drag) on the robot pushes it away from the camera.
  let down = null;
  canvas.addEventListener('pointerdown', (event) => { down = { x: event.clientX, y: event.clientY }; });
  canvas.addEventListener('pointerup', guard('drive push', (event) => {
    if (!down || Math.hypot(event.clientX - down.x, event.clientY - down.y) > CLICK_SLOP) return;
    const direction = pushDirection(event);
    if (direction === null) return;
    let heading = direction - robotYaw();
    heading = Math.atan2(Math.sin(heading), Math.cos(heading));
    message(K.push, { [K.heading]: heading });
  }));

  function show() {
    const roleText = {
      [K.driver]: 'you drive', [K.watcher]: 'watching: another page drives', [K.free]: 'nobody drives: press a key',
    }[state.role] ?? 'connecting…';
    const latency = state.latencies.length > 0 ? ` · key→sim ${state.latencies[state.latencies.length - 1].toFixed(0)} ms` : '';
    const last = state.refusals[state.refusals.length - 1];
    const refusal = last && performance.now() - last.at < 3000 ? ` · refused: ${last.reason}` : '';
    const height = hasHeight
      ? ` · height ${(limits.min_height + state.height * (limits.max_height - limits.min_height)).toFixed(2)} m (Q/Z)`
      : '';
    hud.setDrive(`${roleText}${state.paused ? ' · paused' : ''}${height}${latency}${refusal}`,
      state.role === K.driver ? 'ok' : 'idle');
  }

  /** A text message of the server that is not the end of the run. */
  function onMessage(received) {
    const type = received[K.type];
    if (type === K.status) {
      state.role = received[K.role];
      state.paused = Boolean(received[K.paused]);
      state.reason = String(received[K.reason] ?? '');
      // Control changed hands (or the page reconnected): the held command is sent once
      // more, which takes the controls when they are free.
      if (state.role !== K.driver) {
        state.command = { forward: 0, yaw: 0, height: state.height };
        attempted = state.command;
      }
    } else if (type === K.refused) {
      pushBounded(state.refusals, { reason: String(received[K.reason] ?? ''), at: performance.now() });
      if (state.role !== K.driver) state.command = { forward: 0, yaw: 0, height: state.height };
    } else if (type === K.applied) {
      const seq = received[K.seq];
      if (pressedAt.has(seq)) {
        pushBounded(state.latencies, performance.now() - pressedAt.get(seq));
        for (const key of pressedAt.keys()) if (key <= seq) pressedAt.delete(key);
      }
    }
    show();
  }

  hud.setKeys(KEY_LEGEND);
  show();
  return { state, onMessage };
}
