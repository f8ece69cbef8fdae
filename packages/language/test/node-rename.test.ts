/** `planRename` (contract rename): the editor's rename rules and edits on a workspace loaded from disk. */
import { cpSync, mkdtempSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { beforeAll, describe, expect, it } from 'vitest';
import { loadWorkspace, type LoadedWorkspace } from '../src/node/load-workspace.js';
import { planRename } from '../src/node/rename-entity.js';
import { renameInScenarios } from '../src/node/rename-scenarios.js';

const TUTORIAL = fileURLToPath(new URL('../../../examples/tutorial', import.meta.url));
const MOBILE_ROBOT = fileURLToPath(new URL('../../../examples/mobile-robot', import.meta.url));
let ws: LoadedWorkspace;
beforeAll(async () => { ws = await loadWorkspace(TUTORIAL); });

describe('planRename', () => {
    it('a module: every reference in every file, nothing else', () => {
        const plan = planRename(ws, 'MSC', 'MSK');
        expect(plan).toMatchObject({ kind: 'module', oldName: 'MSC', newName: 'MSK', generatedNames: true });
        expect(plan.files.map((f) => f.file)).toEqual(['sched.contract', 'smodule3.contract', 'sschema1.contract', 'sschema2.contract', 'supervisor.contract']);
        for (const f of plan.files) {
            const before = ws.documents.find((d) => d.file === f.file)!.document.textDocument.getText();
            expect(f.text).toBe(before.replace(/\bMSC\b/g, 'MSK'));
            expect(f.occurrences).toBe(before.match(/\bMSC\b/g)!.length);
        }
    });

    it('a port by MODULE:name or by an index only one port has; a supervision function by SUP.function; its members by SUP.function.NAME; each with its owner', () => {
        const port = planRename(ws, 'MSC:in_coordinates', 'position');
        expect(port).toMatchObject({ kind: 'port', oldName: 'in_coordinates', generatedNames: false, owner: 'MSC' });
        expect(port.files.map((f) => f.file)).toEqual(['smodule3.contract']);
        expect(planRename(ws, 'SUP:2', 'link')).toMatchObject({ oldName: 'connection_status', owner: 'SUP' });
        expect(planRename(ws, 'SUP.action', 'act')).toMatchObject({ kind: 'supervision function', generatedNames: false, owner: 'SUP' });
        expect(planRename(ws, 'SUP.action.FIRST', 'OPENING')).toMatchObject({ kind: 'rule label', owner: 'SUP.action' });
        expect(planRename(ws, 'SUP.action.temp_mess_type', 'kind')).toMatchObject({ kind: 'local', owner: 'SUP.action' });
        expect(planRename(ws, 'SUP.action.consigne', 'setpoint')).toMatchObject({ kind: 'function parameter', owner: 'SUP.action' });
        const type = planRename(ws, 'TypeA', 'Vec3');
        expect(type).toMatchObject({ kind: 'datatype', generatedNames: true });
        expect(type.owner).toBeUndefined();
        expect(planRename(ws, 'schemaCommande1', 'command1')).toMatchObject({ kind: 'schema', generatedNames: false });
    });

    it('a schema: also the strings an ORD event test compares ord_schema with, not other strings', async () => {
        const dir = mkdtempSync(join(tmpdir(), 'rename-ord-'));
        try {
            cpSync(TUTORIAL, dir, { recursive: true, filter: (src) => !/\/(src-gen|logs)$/.test(src) });
            const file = join(dir, 'supervisor.contract');
            writeFileSync(file, readFileSync(file, 'utf8')
                .replace('[started(THIRD)]', '[ORD:0<ord_schema == "schemaCommande1"> or started(THIRD)]')
                .replace('temp_mess_type = "commutation"', 'temp_mess_type = "schemaCommande1"'));
            const plan = planRename(await loadWorkspace(dir), 'schemaCommande1', 'command1');
            const sup = plan.files.find((f) => f.file === 'supervisor.contract')!;
            expect(sup.text).toContain('[ORD:0<ord_schema == "command1"> or started(THIRD)]');
            expect(sup.text).toContain('temp_mess_type = "schemaCommande1"'); // a string, not a test of ord_schema
            expect(sup.occurrences).toBe(2); // the activation and the ORD test
        } finally {
            rmSync(dir, { recursive: true, force: true });
        }
    });

    it('clear errors: unknown entity, ambiguous index, invalid name, name taken', () => {
        expect(() => planRename(ws, 'MSX', 'MSK')).toThrow("no module, supervisor, schema, datatype, enumeration or function named 'MSX'");
        expect(() => planRename(ws, 'MSC:9', 'x')).toThrow('MSC has no port or parameter \'9\'; its ports and parameters: param (parameter :0), in_coordinates (in data port :0)');
        expect(() => planRename(ws, 'MSC:1', 'x')).toThrow("'MSC:1' is ambiguous: out_coordinates_commmmand (out data port :1), failing_data (out event port :1)");
        expect(() => planRename(ws, 'MSC', 'msk')).toThrow("'msk' is not a valid module name: module and supervisor names are exactly three upper-case letters");
        expect(() => planRename(ws, 'MSC', 'MSD')).toThrow("'MSD' already names a module or supervisor (in smodule4.contract)");
        expect(() => planRename(ws, 'TypeA', 'struct')).toThrow("'struct' is a C keyword");
        expect(() => planRename(ws, 'SUP.nope', 'x')).toThrow('supervisor SUP has no function \'nope\'; its functions: action');
    });

    it('an enumeration by its name (its members with it, for their C constants); a member by ENUM.MEMBER, owned by its enumeration', async () => {
        const robot = await loadWorkspace(MOBILE_ROBOT);
        const enumeration = planRename(robot, 'DriveMode', 'Mode');
        expect(enumeration).toMatchObject({ kind: 'enumeration', oldName: 'DriveMode', generatedNames: true, members: ['TELEOP', 'AUTO', 'SAFESTOP'] });
        expect(enumeration.owner).toBeUndefined();
        expect(enumeration.files.map((f) => f.file)).toEqual(['control-loop.contract', 'drive.contract', 'types.contract', 'velocity.contract']);
        const member = planRename(robot, 'DriveMode.AUTO', 'AUTONOMOUS');
        expect(member).toMatchObject({ kind: 'enumeration member', oldName: 'AUTO', generatedNames: false, owner: 'DriveMode' });
        expect(member.members).toBeUndefined();
        const drive = member.files.find((f) => f.file === 'drive.contract')!;
        expect(drive.text).toContain('mode = DriveMode.AUTONOMOUS)');
        expect(drive.text).not.toMatch(/DriveMode\.AUTO\b/);
        expect(member.files.find((f) => f.file === 'types.contract')!.text).toContain('enum DriveMode { TELEOP, AUTONOMOUS, SAFESTOP }');
        expect(() => planRename(robot, 'DriveMode.FAST', 'X')).toThrow("enumeration DriveMode has no member 'FAST'; its members: TELEOP, AUTO, SAFESTOP");
        expect(() => planRename(robot, 'DriveMod.AUTO', 'X')).toThrow("no supervisor or enumeration named 'DriveMod' (in 'DriveMod.AUTO': 'SUPERVISOR.function' or 'ENUM.MEMBER'). Did you mean 'DriveMode'?");
        expect(() => planRename(robot, 'DriveMode.AUTO', 'TELEOP')).toThrow("'TELEOP' is already used by another member");
        // an element of another kind that a rename finds by name alone: the two could not be told apart afterwards
        expect(() => planRename(robot, 'DriveMode', 'LOC')).toThrow("'LOC' already names a module (in localisation.contract): two elements of one name could not be told apart by a rename; choose another name.");
        expect(() => planRename(robot, 'DriveMode', 'obstacleWatch')).toThrow("'obstacleWatch' already names");
    });

    it('a scenario\'s Mode.AUTO values follow an enumeration\'s rename and a member\'s (of that enumeration only)', () => {
        const dir = mkdtempSync(join(tmpdir(), 'rename-enum-scenario-'));
        try {
            const file = join(dir, 'modes.scenario');
            writeFileSync(file, 'scenario S\nt=1s CTL:0 DriveMode.AUTO\nt=2s CTL:0 Gear.AUTO\nexpect local DRV.f.mode == DriveMode.AUTO\n');
            const renamed = renameInScenarios(dir, [file], { kind: 'enumeration', oldName: 'DriveMode', newName: 'Mode' });
            expect(renamed[0]!.text).toBe('scenario S\nt=1s CTL:0 Mode.AUTO\nt=2s CTL:0 Gear.AUTO\nexpect local DRV.f.mode == Mode.AUTO\n');
            const member = renameInScenarios(dir, [file], { kind: 'enumeration member', oldName: 'AUTO', newName: 'AUTONOMOUS', owner: 'DriveMode' });
            expect(member[0]!.text).toBe('scenario S\nt=1s CTL:0 DriveMode.AUTONOMOUS\nt=2s CTL:0 Gear.AUTO\nexpect local DRV.f.mode == DriveMode.AUTONOMOUS\n');
            expect(member[0]!.edits.map((e) => e.line)).toEqual([2, 4]);
        } finally {
            rmSync(dir, { recursive: true, force: true });
        }
    });
});
