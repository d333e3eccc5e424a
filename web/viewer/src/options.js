// Query parameters, for tests and users: robot=0, follow=0, plots=0, autoplay=0, t=SECONDS.
const params = new URLSearchParams(window.location.search);

function flag(name) {
  return params.get(name) !== '0';
}

function number(name) {
  const value = Number.parseFloat(params.get(name) ?? '');
  return Number.isFinite(value) ? value : null;
}

export const options = {
  robot: flag('robot'),
  follow: flag('follow'),
  plots: flag('plots'),
  autoplay: flag('autoplay'),
  startTime: number('t'),
};
