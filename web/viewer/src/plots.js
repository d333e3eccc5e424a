// Time plots (uPlot) of pitch, ground position and actions. Live: a sliding window over the
// current episode. Replay: the whole episode with a marker at the time drawn.
import uPlot from 'uplot';
import { tickLabels } from './ticks.js';

const LIVE_WINDOW = 10.0;  // seconds of the current episode kept in live plots
// Least height of a chart's drawing area [CSS px]: the actions chart, whose legend of six
// names took most of its share of the panel, drew its curves in 15 px, flat. The panel
// scrolls when the charts do not fit.
const MIN_PLOT_AREA = 60;
const ACTION_COLORS = ['#e8590c', '#7048e8', '#d6336c', '#1098ad', '#5c940d', '#495057'];

function chartSpecs(layout) {
  const specs = [
    { title: 'Pitch [rad]', series: [{ label: 'pitch', index: layout.index.pitch, stroke: '#1c7ed6' }] },
    {
      title: 'Ground position [m]',
      series: [{ label: 'position', index: layout.index.ground_position, stroke: '#0ca678' }],
    },
  ];
  // Charts the session asks for, e.g. command against measured velocity.
  const colors = ['#e03131', '#1c7ed6'];
  for (const chart of layout.charts) {
    specs.push({
      title: chart.title,
      series: chart.series.map(({ label, field }, i) => ({
        label, index: layout.index[field], stroke: colors[i % colors.length],
      })),
    });
  }
  if (layout.actions.length > 0) {
    specs.push({
      title: 'Actions',
      series: layout.actions.map(([name, index], i) => ({
        label: name, index, stroke: ACTION_COLORS[i % ACTION_COLORS.length],
      })),
    });
  }
  return specs;
}

/** Height of a chart's drawing area between its axes [CSS px] (uPlot's bbox is in device px). */
function plotArea(plot) {
  return plot.bbox.height / (window.devicePixelRatio || 1);
}

/** An axis named `label` whose tick labels go through tickLabels and into `drawn`. */
const axis = (label, drawn) => ({
  label,
  values: (plot, splits, axisIndex, space, increment) => {
    drawn[axisIndex] = tickLabels(splits, increment);
    return drawn[axisIndex];
  },
  labelSize: 18,
  labelFont: '11px system-ui, sans-serif',
  font: '11px system-ui, sans-serif',
  stroke: '#495057',
  grid: { stroke: '#e9ecef', width: 1 },
  ticks: { stroke: '#ced4da', width: 1, size: 4 },
});

export function createPlots(panel, layout) {
  const timeIndex = layout.index.time;
  const specs = chartSpecs(layout);
  const charts = specs.map((spec, chartIndex) => {
    const drawn = [[], []];  // the tick labels last drawn: time axis, value axis
    const wrapper = document.createElement('div');
    wrapper.className = 'plot';
    panel.append(wrapper);
    const plot = new uPlot({
      title: spec.title,
      width: 300,
      height: 150,
      scales: { x: { time: false } },
      cursor: { drag: { x: false, y: false } },
      // Titles name single curves; only several actions need a legend.
      legend: { show: spec.series.length > 1, live: false },
      series: [
        { label: 'time' },
        ...spec.series.map(({ label, stroke }) => ({ label, stroke, width: 1.5 })),
      ],
      // The charts share their time axis: the last one names it.
      axes: [axis(chartIndex === specs.length - 1 ? 'time [s]' : null, drawn),
        // Ticks 20 px apart at least: three or more on the smallest chart.
        { ...axis(null, drawn), size: 52, space: 20 }],
    }, [[], ...spec.series.map(() => [])], wrapper);
    const marker = document.createElement('div');
    marker.className = 'plot-marker';
    marker.hidden = true;
    plot.over.append(marker);
    return { spec, wrapper, plot, marker, drawn, columns: [[], ...spec.series.map(() => [])] };
  });

  // Fit each chart to its share of the panel, its drawing area at least MIN_PLOT_AREA: what
  // uPlot draws outside its canvas (title, legend) and around the drawing area (axes) does
  // not depend on the canvas height.
  function fit() {
    for (const { wrapper, plot } of charts) {
      const extra = plot.root.offsetHeight - plot.height;
      const axes = plot.height - plotArea(plot);
      const least = Math.ceil(MIN_PLOT_AREA + axes);
      wrapper.style.minHeight = `${least + extra}px`;
      const width = wrapper.clientWidth;
      const height = Math.max(least, wrapper.clientHeight - extra);
      if (width > 0 && (width !== plot.width || height !== plot.height)) {
        plot.setSize({ width, height });
      }
    }
  }
  new ResizeObserver(fit).observe(panel);
  // uPlot sizes its axes once it has data: the first fit cannot know them.
  function fitIfSqueezed() {
    if (charts.some(({ plot }) => plotArea(plot) < MIN_PLOT_AREA - 0.5)) fit();
  }

  let dirty = false;
  let lastEpisode = null;
  let lastStep = null;

  /** Live: appends one frame row, starting over at a new episode. */
  function append(data, offset) {
    const episode = data[offset + layout.index.episode];
    const step = data[offset + layout.index.step];
    if (episode !== lastEpisode || step < lastStep) {
      for (const chart of charts) chart.columns.forEach((column) => { column.length = 0; });
    }
    lastEpisode = episode;
    lastStep = step;
    for (const { spec, columns } of charts) {
      columns[0].push(data[offset + timeIndex]);
      spec.series.forEach(({ index }, i) => columns[i + 1].push(data[offset + index]));
    }
    dirty = true;
  }

  /** Live: redraws once per animation frame what append() brought, the last 10 s only. */
  function flush() {
    if (!dirty) return;
    dirty = false;
    for (const { plot, columns } of charts) {
      const times = columns[0];
      const first = times.findIndex((t) => t >= times[times.length - 1] - LIVE_WINDOW);
      if (first > 0) columns.forEach((column) => column.splice(0, first));
      plot.setData(columns);
    }
    fitIfSqueezed();
  }

  /** Replay: shows the `count` frame rows of `data` (a whole episode). */
  function showEpisode(data, count) {
    for (const { spec, plot } of charts) {
      const columns = [new Float64Array(count), ...spec.series.map(() => new Float64Array(count))];
      for (let row = 0; row < count; row++) {
        const offset = row * layout.size;
        columns[0][row] = data[offset + timeIndex];
        spec.series.forEach(({ index }, i) => { columns[i + 1][row] = data[offset + index]; });
      }
      plot.setData(columns);
    }
    fitIfSqueezed();
  }

  /** Replay: the vertical marker at time `t`. */
  function mark(t) {
    for (const { plot, marker } of charts) {
      const left = plot.valToPos(t, 'x');
      marker.hidden = !Number.isFinite(left);
      marker.style.transform = `translateX(${left}px)`;
    }
  }

  /**
   * Each chart's title, drawing-area height [CSS px], the tick labels it last drew and its
   * series' ranges (tests).
   */
  function describe() {
    return charts.map(({ spec, drawn, plot }) => ({
      title: spec.title,
      plotArea: plotArea(plot),
      timeTicks: drawn[0],
      valueTicks: drawn[1],
      series: spec.series.map(({ label }, i) => {
        const values = Array.from(plot.data[i + 1] ?? []).filter(Number.isFinite);
        return { label, min: values.reduce((a, b) => Math.min(a, b), Infinity),
          max: values.reduce((a, b) => Math.max(a, b), -Infinity) };
      }),
    }));
  }

  return { append, flush, showEpisode, mark, fit, describe };
}
