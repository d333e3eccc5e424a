// The real `upkie-rl` binary (UPKIE_RL_CLI) for the browser tests: run to completion, or
// serve a page and hand back its URL.
import { spawn } from 'node:child_process';

export const CLI = process.env.UPKIE_RL_CLI;
if (!CLI) throw new Error('set UPKIE_RL_CLI to the upkie-rl binary');

/** Runs upkie-rl to completion; rejects with its output on failure. */
export function run(args) {
  return new Promise((resolve, reject) => {
    const child = spawn(CLI, args);
    let output = '';
    child.stdout.on('data', (data) => { output += data; });
    child.stderr.on('data', (data) => { output += data; });
    child.on('close', (code) => (code === 0 ? resolve(output)
      : reject(new Error(`upkie-rl ${args.join(' ')}: exit ${code}\n${output}`))));
  });
}

/**
 * Starts upkie-rl and resolves once it prints its viewer URL, with the child, the URL,
 * `exited` (resolves to {code, signal, output}) and `output()` (printed so far).
 */
export function serve(args) {
  return new Promise((resolve, reject) => {
    const child = spawn(CLI, args);
    let output = '';
    const exited = new Promise((done) => child.on('close', (code, signal) => done({ code, signal, output })));
    const onData = (data) => {
      output += data;
      const match = output.match(/viewer: (http:\/\/\S+\/)/);
      if (match) resolve({ child, url: match[1], exited, output: () => output });
    };
    child.stdout.on('data', onData);
    child.stderr.on('data', onData);
    child.on('close', (code) => reject(new Error(`upkie-rl exited (${code}) before serving:\n${output}`)));
  });
}
