// Replay controls under the scene: play/pause, episode, time slider, speed.
import { guard } from './errors.js';
import { SPEEDS } from './replay_source.js';

function element(tag, props = {}, children = []) {
  const node = Object.assign(document.createElement(tag), props);
  node.append(...children);
  return node;
}

export function createReplayBar(root, replay) {
  const { state } = replay;
  const play = element('button', { type: 'button', className: 'play', title: 'Play/pause (space)' });
  const episode = element('select', { title: 'Episode' }, state.episodes.map(({ episode: number }, i) =>
    element('option', { value: String(i), textContent: `Episode ${number}` })));
  const slider = element('input', { type: 'range', title: 'Time', step: 'any' });
  const clock = element('span', { className: 'clock' });
  const speed = element('select', { title: 'Speed' }, SPEEDS.map((value) =>
    element('option', { value: String(value), textContent: `${value}×` })));
  root.append(play, episode, slider, clock, speed);
  root.hidden = false;

  let scrubbing = false;
  let shownEpisode = -1;

  play.addEventListener('click', guard('play button', () => replay.setPlaying(!state.playing)));
  episode.addEventListener('change', guard('episode selector', () => {
    replay.selectEpisode(Number(episode.value));
  }));
  slider.addEventListener('pointerdown', () => { scrubbing = true; });
  slider.addEventListener('pointerup', () => { scrubbing = false; });
  slider.addEventListener('change', () => { scrubbing = false; });
  slider.addEventListener('input', guard('time slider', () => replay.seek(Number(slider.value))));
  speed.addEventListener('change', guard('speed selector', () => replay.setSpeed(Number(speed.value))));
  window.addEventListener('keydown', guard('keyboard', (event) => {
    // Controls handle their own keys (a focused button already toggles on space).
    if (event.code !== 'Space' || event.target.closest('button, select, input')) return;
    event.preventDefault();
    replay.setPlaying(!state.playing);
  }));

  function sync() {
    play.textContent = state.playing ? '❚❚' : '▶';
    play.setAttribute('aria-label', state.playing ? 'Pause' : 'Play');
    speed.value = String(state.speed);
    if (state.episodeIndex !== shownEpisode) {
      shownEpisode = state.episodeIndex;
      episode.value = String(shownEpisode);
      const [first, last] = replay.bounds();
      slider.min = String(first);
      slider.max = String(last);
    }
  }
  replay.onChange(sync);
  sync();

  return {
    /** Follows playback; called at each drawn frame. */
    update() {
      const [, last] = replay.bounds();
      if (!scrubbing) slider.value = String(state.playTime);
      clock.textContent = `${state.playTime.toFixed(2)} / ${last.toFixed(2)} s`;
    },
  };
}
