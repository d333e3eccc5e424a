// Replay of the session's recorded episodes in real time × speed, following frame times.
// At the end of an episode it goes on with the next one, and pauses after the last.
export const SPEEDS = [0.25, 0.5, 1, 2, 4, 8];

export function createReplaySource(session, layout, { autoplay, startTime }) {
  const timeIndex = layout.index.time;
  const episodes = session.episodes
    .map(({ episode, frames }) => {
      const data = Float64Array.from(frames);
      const count = data.length / layout.size;
      return { episode, data, count };
    })
    .filter(({ count }) => count > 0);
  if (episodes.length === 0) throw new Error('replay session has no frames');

  const time = (episode, row) => episode.data[row * layout.size + timeIndex];
  const listeners = [];

  const state = {
    episodes,
    episodeIndex: 0,
    row: 0,
    playTime: 0,
    playing: autoplay,
    speed: 1,
    framesReceived: episodes.reduce((sum, { count }) => sum + count, 0),
  };

  const current = () => episodes[state.episodeIndex];

  /** Last row at or before time t (frames are in time order). */
  function rowAt(episode, t) {
    let [low, high] = [0, episode.count - 1];
    if (t <= time(episode, 0)) return 0;
    while (low < high) {
      const middle = (low + high + 1) >> 1;
      if (time(episode, middle) <= t) low = middle;
      else high = middle - 1;
    }
    return low;
  }

  function notify() {
    for (const listener of listeners) listener(state);
  }

  function seek(t) {
    const episode = current();
    const first = time(episode, 0);
    const last = time(episode, episode.count - 1);
    state.playTime = Math.min(Math.max(t, first), last);
    state.row = rowAt(episode, state.playTime);
  }

  function selectEpisode(index) {
    state.episodeIndex = index;
    seek(-Infinity);
    notify();
  }

  /** Moves playback on by `seconds` of wall-clock time. */
  function advance(seconds) {
    if (!state.playing) return;
    const episode = current();
    const target = state.playTime + seconds * state.speed;
    if (target <= time(episode, episode.count - 1)) {
      seek(target);
    } else if (state.episodeIndex + 1 < episodes.length) {
      selectEpisode(state.episodeIndex + 1);
    } else {
      seek(target);
      state.playing = false;
      notify();
    }
  }

  function setPlaying(playing) {
    // Play at the end of the last episode starts over from the first one.
    const episode = current();
    if (playing && state.row === episode.count - 1 && state.episodeIndex === episodes.length - 1) {
      state.episodeIndex = 0;
      seek(-Infinity);
    }
    state.playing = playing;
    notify();
  }

  function setSpeed(speed) {
    state.speed = speed;
    notify();
  }

  seek(startTime ?? -Infinity);

  return {
    state,
    advance,
    seek,
    selectEpisode,
    setPlaying,
    setSpeed,
    /** The frame row to draw: {data, offset}. */
    frame: () => ({ data: current().data, offset: state.row * layout.size }),
    bounds: () => [time(current(), 0), time(current(), current().count - 1)],
    onChange: (listener) => listeners.push(listener),
  };
}
