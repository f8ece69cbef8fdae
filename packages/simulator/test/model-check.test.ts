/** Scenario names and values are checked against the project, with file:line:col diagnostics. */
import { describe, expect, it } from 'vitest';
import { loadScenario } from '../src/index.js';
import { prepared, TUTORIAL } from './support.js';

describe('checkScenario on the tutorial', () => {
    it('names what is wrong, where, and what was expected', async () => {
        const project = await prepared(TUTORIAL);
        const text = [
            'start SUP.action(consigne = "far", speed = 3)',  // 1: string for TypeA; unknown parameter
            'start SUP.nope()',                                // 2
            't=1ms MAA:7 "x"',                                 // 3: no out event port 7
            't=2ms MAA:2 status = 3',                          // 4: port name and type
            'expect rule SUP.action.FIFTH active',             // 5
            'expect local temp_consigne == {1.0, 2.0}',        // 6: TypeA has 3 fields
            'expect local nothing == 1',                       // 7
            'exec MAA 2ms',                                    // 8: fine (each event MAA handles)
            't=3ms ORD:0 "noSchema"',                          // 9
            'expect schema schemaCommande1 active',            // 10: fine
            'expect module ZZZ running',                       // 11
            'finish MSA',                                      // 12: synchronous
            'finish MAA',                                      // 13: fine
            'expect deadline misses schemaReceptionMessage == 0', // 14: an event schema
            'expect overruns schemaCommande3 == 0',             // 15
            'expect overruns schemaCommande1 == 0',             // 16: fine
        ].join('\n');
        const s = loadScenario('x.scenario', 'x.scenario', text, project.index);
        const d = s.diagnostics.map((x) => `${x.line}:${x.column} ${x.code} ${x.message}`);
        expect(d).toEqual([
            "1:29 scenario-value-type Expected a TypeA value {i, j, k} for parameter 'consigne', found a string.",
            "1:36 scenario-unknown-parameter SUP.action has no parameter 'speed' (parameters: consigne)",
            "2:11 scenario-unknown-function supervisor SUP has no function 'nope' (functions: action)",
            '3:11 scenario-unknown-port MAA has no out event port 7 (out event ports: :0 message_type_notification, :1 received_message, :2 connection_status)',
            "4:13 scenario-port-name MAA:2 is 'connection_status', not 'status'",
            "4:22 scenario-value-type Expected a string (\"...\") for MAA:2 (string connection_status), found the integer 3.",
            "5:24 scenario-unknown-rule SUP.action has no rule 'FIFTH' (rules: FIRST, SECOND, THIRD, FOURTH, RECEPTION)",
            "6:31 scenario-value-type TypeA has 3 fields (i, j, k); this value has 2 elements for local 'temp_consigne'.",
            "7:14 scenario-unknown-local no function of the project has a local 'nothing'",
            "9:13 scenario-unknown-schema no schema 'noSchema' in the project (schemas: schemaReceptionMessage, schemaCommande1, schemaCommande2)",
            "11:15 scenario-unknown-module no module 'ZZZ' in the project (modules: MAA, MAB, MSA, MSB, MSC, MSD)",
            '12:8 scenario-not-asynchronous MSA is a synchronous module: each of its releases ends by itself (exec sets how long one takes); finish ends the run of an asynchronous module',
            '14:24 scenario-not-periodic schemaReceptionMessage is an event schema: it has no period, so no deadline misses nor overruns (ORD counts those of periodic schemas: schemaCommande1, schemaCommande2)',
            "15:17 scenario-unknown-schema no schema 'schemaCommande3' in the project (schemas: schemaReceptionMessage, schemaCommande1, schemaCommande2). Did you mean 'schemaCommande1'?",
        ]);
    });
    it('checks the steps that parsed even when others did not: every problem of the file at once', async () => {
        const project = await prepared(TUTORIAL);
        const text = ['t=2s start SUP.action()', 't=1s expect rule SUP.action.FIRST active', 'expect rule SUP.action.NOPE active'].join('\n');
        const s = loadScenario('x.scenario', 'x.scenario', text, project.index);
        expect(s.diagnostics.map((d) => `${d.line}:${d.code}`)).toEqual(['2:scenario-time-order', '3:scenario-unknown-rule']);
    });
    it('an event from something that emits none lists only those that do', async () => {
        const project = await prepared(TUTORIAL);
        const s = loadScenario('x.scenario', 'x.scenario', 'MSZ:0 1', project.index);
        const message = s.diagnostics.find((d) => d.code === 'scenario-unknown-module')!.message;
        const listed = /those that do: ([^)]*)\)/.exec(message)![1]!.split(', ');
        // MSA... are synchronous modules of the tutorial without out event ports: not offered
        for (const name of listed) {
            const owner = project.index.modules.get(name) ?? project.index.supervisors.get(name);
            expect(owner, name).toBeDefined();
        }
        expect(listed).toContain('MAA');
        expect(listed).toContain('SUP');
        expect(listed.length).toBeLessThan(project.index.modules.size + project.index.supervisors.size);
    });
});
