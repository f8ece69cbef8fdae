/** Model helpers shared with code generation: time literals, ports by index, values and defaults. */
import { beforeAll, describe, expect, it } from 'vitest';
import { isDataType, isModule, type DataType, type Model, type Module } from '../src/generated/ast.js';
import { computeTimeNs, formatNanoseconds, parseTime, timeToNanoseconds } from '../src/model/index.js';
import { portsOf, resolveParameter, resolvePort } from '../src/model/ports.js';
import { typeOf } from '../src/model/types.js';
import { defaultValue, effectiveValue, formatConstant } from '../src/model/values.js';
import { build, TYPES } from './helpers.js';

describe('time literals', () => {
    it('converts every unit to nanoseconds', () => {
        expect(timeToNanoseconds('500us')).toBe(500_000);
        expect(timeToNanoseconds('1.5ms')).toBe(1_500_000);
        expect(timeToNanoseconds('1s')).toBe(1_000_000_000);
        expect(timeToNanoseconds('7ns')).toBe(7);
        expect(timeToNanoseconds('-2ms')).toBe(-2_000_000);
        expect(Number.isNaN(timeToNanoseconds('5'))).toBe(true);
        expect(parseTime('2.25s')).toEqual({ amount: 2.25, unit: 's' });
        expect(formatNanoseconds(1_500_000)).toBe('1500us');
        expect(formatNanoseconds(2_000_000_000)).toBe('2s');
    });
});

describe('ports, values and defaults', () => {
    let model: Model;
    beforeAll(async () => {
        const built = await build({
            't.contract': TYPES + '\ndatatype TypeE {TypeC message, TypeD data_};',
            'm.contract': `import "t.contract";
synchronous module MSC {
    parameters { TypeA param = {2.1,6.98,5} :0; int gain :1; }
    scheduling { C=500us; }
    data flows { in :0 TypeA in_c; out :1 TypeB out_c; }
    event flows { out :1 TypeD failing; }
}`
        });
        expect(built.lines).toEqual([]);
        model = built.docs.get('m.contract')!.parseResult.value;
        types = built.docs.get('t.contract')!.parseResult.value.elements.filter(isDataType);
    });
    let types: DataType[];

    it('resolves ports by index, kind and direction', () => {
        const m = model.elements[0] as Module;
        expect(isModule(m)).toBe(true);
        expect(portsOf(m).map((p) => `${p.kind}:${p.direction}:${p.index}:${p.port.name}`)).toEqual(['data:in:0:in_c', 'data:out:1:out_c', 'event:out:1:failing']);
        expect(resolvePort(m, 1, 'data', 'out')?.name).toBe('out_c');
        expect(resolvePort(m, 1, 'event', 'out')?.name).toBe('failing');
        expect(resolvePort(m, 1, 'data', 'in')).toBeUndefined();
        expect(resolveParameter(m, 1)?.name).toBe('gain');
        expect(computeTimeNs(m)).toBe(500_000);
    });

    it('gives written values (int literal as float) and defaults (0, 0.0, "", datatype defaults)', () => {
        const m = model.elements[0] as Module;
        const param = resolveParameter(m, 0)!;
        expect(formatConstant(effectiveValue(param)!)).toBe('{2.1,6.98,5.0}');
        expect(formatConstant(effectiveValue(resolveParameter(m, 1)!)!)).toBe('0');
        const typeB = types.find((t) => t.name === 'TypeB')!;
        expect(formatConstant(defaultValue(typeOf({ $type: 'TypeRef', datatype: { ref: typeB } } as never))!)).toBe('{{1.0,1.0,1.0},1}');
        const typeE = types.find((t) => t.name === 'TypeE')!;
        expect(formatConstant(defaultValue({ kind: 'struct', datatype: typeE })!)).toBe('{{"",0,{0.0,0.0,0.0}},{"",0}}');
    });
});
