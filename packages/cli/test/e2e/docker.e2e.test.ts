/**
 * Both examples in the docker sandbox, in one file so the Docker engine is brought up once
 * (scripts/docker-up.sh: starts dockerd, makes the contract-gcc image) and stopped only after every
 * docker step (when this file started it). Without a usable engine: DOCKER TESTS SKIPPED, loudly.
 */
import { readdirSync, readFileSync } from 'node:fs';
import { join } from 'node:path';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { isSubsequence } from './csv-log.js';
import { dockerUp, type DockerEnv } from '@contract-studio/build-service/test-support/docker-env';
import { contract, scratchCopy, type RunJson, type Scratch } from './harness.js';

let docker: DockerEnv;
let tutorial: Scratch;
let robot: Scratch;
beforeAll(() => {
    docker = dockerUp();
    tutorial = scratchCopy('tutorial');
    robot = scratchCopy('mobile-robot');
}, 320_000);
afterAll(() => {
    docker?.stop();
    tutorial?.dispose();
    robot?.dispose();
});

describe('the examples in the docker sandbox', () => {
    it('builds the tutorial', (ctx) => {
        if (!docker.available) return ctx.skip();
        const r = contract(['build', 'tutorial', '--sandbox', 'docker', '--format', 'json'], tutorial);
        const json = JSON.parse(r.stdout) as RunJson;
        expect(json.sandbox).toBe('docker');
        expect(json.result.message).toMatch(/build succeeded/);
        expect(r.code).toBe(0);
    }, 300_000);

    it('builds the mobile robot with no gcc warning and runs it 7 s through the same supervisor sequence', (ctx) => {
        if (!docker.available) return ctx.skip();
        const build = contract(['build', 'mobile-robot', '--sandbox', 'docker', '--format', 'json'], robot);
        const built = JSON.parse(build.stdout) as RunJson;
        expect(built.result.message).toMatch(/build succeeded/);
        expect(built.diagnostics).toEqual([]);
        expect(build.code).toBe(0);

        const run = contract(['run', 'mobile-robot', '--sandbox', 'docker', '--duration', '7s', '--logs', robot.logs, '--format', 'json'], robot);
        const ran = JSON.parse(run.stdout) as RunJson;
        expect(ran.result.message).toBe('run finished (exit 0)');
        expect(ran.moduleFailures).toEqual([]);
        const mis = ran.output.filter((l) => l.source === 'MIS').map((l) => l.line);
        expect(isSubsequence(mis, [
            'rule mission.TELEOP active', 'rule mission.TELEOP inactive', 'rule mission.AUTO active',
            'rule mission.AUTO inactive', 'rule mission.STOP active', 'rule mission.STOP inactive', 'rule mission.AUTO active',
        ])).toBe(true);
        expect(ran.output.some((l) => l.source === 'OBS' && l.line === 'OBS: obstacle ahead (nearest 0.35 m)')).toBe(true);
        expect(ran.output.some((l) => l.source === 'launcher' && l.line === 'all modules stopped cleanly')).toBe(true);
        expect(run.code).toBe(0);
        // the CSV logs come out of the container volume (build service artifacts), one per module
        expect(ran.logsDir).toBe(robot.logs);
        expect(ran.runDirLeftovers).toEqual([]);
        // beside them, the launcher's own lines (contract-launch.log), not counted among the logs
        expect(readdirSync(robot.logs).sort()).toEqual([...ran.logs, 'contract-launch.log'].sort());
        const misLog = ran.logs.find((f) => f.startsWith('MIS_'))!;
        expect(readFileSync(join(robot.logs, misLog), 'utf8')).toContain('function mission() started');
    }, 300_000);
});
