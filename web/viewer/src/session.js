// The session document: inlined in the page (self-contained replay) or served beside it.
const REQUIRED_FIELDS = [
  'episode', 'step', 'time', 'return', 'pitch', 'ground_position',
  'base_x', 'base_y', 'base_z', 'base_qw', 'base_qx', 'base_qy', 'base_qz',
];
export const JOINT_NAMES = [
  'left_hip', 'left_knee', 'left_wheel', 'right_hip', 'right_knee', 'right_wheel',
];

export async function loadSession() {
  const inline = document.getElementById('upkie-session');
  let session;
  if (inline) {
    session = JSON.parse(inline.textContent);
  } else {
    const response = await fetch('session.json', { cache: 'no-store' });
    if (!response.ok) throw new Error(`session.json: HTTP ${response.status}`);
    session = await response.json();
  }
  checkSession(session);
  return session;
}

function checkSession(session) {
  if (session.version !== 1) throw new Error(`unsupported session version ${session.version}`);
  if (session.mode !== 'live' && session.mode !== 'replay') {
    throw new Error(`unknown session mode ${JSON.stringify(session.mode)}`);
  }
  const fields = session.frame_fields;
  if (!Array.isArray(fields)) throw new Error('session has no frame_fields');
  for (const name of REQUIRED_FIELDS) {
    if (!fields.includes(name)) throw new Error(`frame_fields lacks "${name}"`);
  }
  if (typeof session.urdf !== 'string') throw new Error('session has no urdf');
  if (session.drive !== undefined && (typeof session.drive.keys !== 'object'
    || typeof session.drive.limits !== 'object')) {
    throw new Error('session has a drive section without keys or limits');
  }
  if (session.mode === 'replay') {
    if (!Array.isArray(session.episodes)) throw new Error('replay session has no episodes');
    for (const { episode, frames } of session.episodes) {
      if (!Array.isArray(frames) || frames.length % fields.length !== 0) {
        throw new Error(`episode ${episode}: frames are not whole rows of frame_fields`);
      }
    }
  } else if (typeof session.websocket !== 'string') {
    throw new Error('live session has no websocket path');
  }
}

/**
 * Where each named field sits in a frame row. Fields are always looked up by name, since the
 * server decides the columns.
 */
export class FrameLayout {
  constructor(session) {
    this.fields = session.frame_fields;
    this.size = this.fields.length;
    this.index = Object.fromEntries(this.fields.map((name, i) => [name, i]));
    this.joints = JOINT_NAMES.filter((name) => name in this.index)
      .map((name) => [name, this.index[name]]);
    const actionNames = session.action_names ?? [];
    this.actions = actionNames.filter((name) => `action.${name}` in this.index)
      .map((name) => [name, this.index[`action.${name}`]]);
    // Charts whose fields are all in the frames.
    this.charts = (session.charts ?? []).filter(({ series }) => Array.isArray(series)
      && series.every(({ field }) => field in this.index));
  }

  /** The value of field `name` in the row of `data` starting at `offset`. */
  get(data, offset, name) {
    return data[offset + this.index[name]];
  }

  /** The row as {name: value}, for the test hook. */
  toObject(data, offset) {
    const frame = {};
    this.fields.forEach((name, i) => { frame[name] = data[offset + i]; });
    return frame;
  }
}
