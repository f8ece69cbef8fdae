import type { Architecture, TypeRef, Value } from '../model/architecture.js';

/** The report's section 8.1 example as a plain model (independent of the parser). */
const A: TypeRef = { datatype: 'TypeA' };
const str: TypeRef = { primitive: 'string' };
const int: TypeRef = { primitive: 'int' };
const flt: TypeRef = { primitive: 'float' };
const r = (value: number): Value => ({ kind: 'real', value });
const s3 = (a: number, b: number, c: number): Value => ({ kind: 'struct', elements: [r(a), r(b), r(c)] });
const v = (name: string, ...path: string[]): Value => ({ kind: 'var', name, path });

export function tutorialModel(): Architecture {
    return {
        datatypes: [
            { name: 'TypeA', fields: [{ name: 'i', type: flt, default: r(0) }, { name: 'j', type: flt, default: r(0) }, { name: 'k', type: flt, default: r(0) }] },
            { name: 'TypeB', fields: [{ name: 'coord', type: A, default: s3(1, 1, 1) }, { name: 'frfrrrf', type: int, default: { kind: 'int', value: 1 } }] },
            { name: 'TypeC', fields: [{ name: 'message', type: str }, { name: 'messagetype', type: int, default: { kind: 'int', value: 0 } }, { name: 'value', type: A }] },
            { name: 'TypeD', fields: [{ name: 'dataname', type: str }, { name: 'datavalue', type: int }] },
            { name: 'TypeE', fields: [{ name: 'message', type: { datatype: 'TypeC' } }, { name: 'data_', type: { datatype: 'TypeD' } }] },
            { name: 'TypeF', fields: [{ name: 'fufu', type: int }, { name: 'juju', type: int }] },
        ],
        functions: [
            { name: 'testit', returns: 'bool', args: [{ name: 'arg1', type: str }, { name: 'arg2', type: A }] },
            { name: 'doit', returns: 'void', args: [{ name: 'argfirst', type: str }, { name: 'argsecond', type: flt }] },
        ],
        modules: [
            { name: 'MAA', kind: 'asynchronous', parameters: [{ name: 'param', index: 0, type: A, initial: s3(22.12, 6.98, 897.34) }], dataIn: [], dataOut: [],
              eventIn: [{ name: 'controlevent', index: 0, type: str }],
              eventOut: [{ name: 'message_type_notification', index: 0, type: { datatype: 'TypeC' } }, { name: 'received_message', index: 1, type: { datatype: 'TypeE' } }, { name: 'connection_status', index: 2, type: str }] },
            { name: 'MAB', kind: 'asynchronous', parameters: [], dataIn: [], dataOut: [], eventIn: [{ name: 'message_type_notification', index: 0, type: { datatype: 'TypeC' } }], eventOut: [] },
            { name: 'MSA', kind: 'synchronous', parameters: [], dataIn: [], dataOut: [{ name: 'coordinates', index: 0, type: A }], eventIn: [], eventOut: [], wcetNs: 500_000 },
            { name: 'MSB', kind: 'synchronous', parameters: [], dataIn: [], dataOut: [{ name: 'coordinates', index: 0, type: A }], eventIn: [], eventOut: [], wcetNs: 500_000 },
            { name: 'MSC', kind: 'synchronous', parameters: [{ name: 'param', index: 0, type: A, initial: s3(2.1, 6.98, 5.34) }], wcetNs: 1_000_000,
              dataIn: [{ name: 'in_coordinates', index: 0, type: A }], dataOut: [{ name: 'out_coordinates_commmmand', index: 1, type: { datatype: 'TypeB' } }],
              eventIn: [], eventOut: [{ name: 'failing_data', index: 1, type: { datatype: 'TypeD' } }] },
            { name: 'MSD', kind: 'synchronous', parameters: [], wcetNs: 1_000_000, dataIn: [{ name: 'in_coordinates_command', index: 2, type: { datatype: 'TypeB' } }], dataOut: [], eventIn: [], eventOut: [] },
        ],
        schemas: [
            { name: 'schemaReceptionMessage', kind: 'event', parameters: [{ name: 'param', type: A, default: s3(27.12, 0, 0.04) }],
              modules: [{ module: 'MAA', settings: [{ port: 0, value: v('param') }] }, { module: 'MAB', settings: [] }], precedences: [], dataFlows: [],
              eventFlows: [{ source: 'MAA', sourcePort: 0, target: 'MAB', targetPort: 0, oneShot: false }] },
            { name: 'schemaCommande1', kind: 'periodic', parameters: [{ name: 'consigne', type: A, default: s3(0, 0, 0) }], periodNs: 1e9, criticalDelayNs: 1e9,
              modules: [{ module: 'MSA', settings: [] }, { module: 'MSC', settings: [{ port: 0, value: v('consigne') }] }, { module: 'MSD', settings: [] }],
              precedences: [{ before: 'MSA', after: 'MSC' }, { before: 'MSC', after: 'MSD' }],
              dataFlows: [{ source: 'MSA', sourcePort: 0, target: 'MSC', targetPort: 0, periodicity: 1 }, { source: 'MSC', sourcePort: 1, target: 'MSD', targetPort: 2, periodicity: 2 }], eventFlows: [] },
            { name: 'schemaCommande2', kind: 'periodic', parameters: [{ name: 'consigne', type: A }], periodNs: 1e9, criticalDelayNs: 1e9,
              modules: [{ module: 'MSB', settings: [] }, { module: 'MSC', settings: [{ port: 0, value: v('consigne') }] }, { module: 'MSD', settings: [] }],
              precedences: [{ before: 'MSB', after: 'MSC' }, { before: 'MSC', after: 'MSD' }],
              dataFlows: [{ source: 'MSB', sourcePort: 0, target: 'MSC', targetPort: 0, periodicity: 1 }, { source: 'MSC', sourcePort: 1, target: 'MSD', targetPort: 2, periodicity: 1 }], eventFlows: [] },
        ],
        scheduler: { modules: ['MSA', 'MSB', 'MSC', 'MSD'], schemas: ['schemaCommande1', 'schemaCommande2'] },
        supervisors: [
            { name: 'SUP',
              eventIn: [{ name: 'message_received', index: 1, type: { datatype: 'TypeC' } }, { name: 'connection_status', index: 2, type: str }, { name: 'failure', index: 3, type: { datatype: 'TypeD' } }],
              eventOut: [{ name: 'failure_message_type', index: 1, type: str }],
              functions: [{ name: 'action', parameters: [{ name: 'consigne', type: A }],
                locals: [{ name: 'temp_message', type: { datatype: 'TypeC' } }, { name: 'temp_mess_type', type: str }, { name: 'failure_data', type: { datatype: 'TypeD' } }, { name: 'temp_consigne', type: A, default: v('consigne') }],
                rules: [
                    { label: 'FIRST', pre: [[{ kind: 'elapsed', timeNs: 1e6, persistence: undefined }]],
                      actions: [{ kind: 'subscribe', source: 'MAA', sourcePort: 2, inPort: 2, oneShot: false }, { kind: 'subscribe', source: 'MAA', sourcePort: 0, inPort: 1, oneShot: false }, { kind: 'schema', schema: 'schemaReceptionMessage', assignments: [] }],
                      post: [[{ kind: 'module', source: 'MAA', port: 2, inPort: 2, tests: [[{ op: '==', left: v('connection_status'), right: { kind: 'string', value: 'disconnected' } }]], persistence: undefined, extractions: [] }]] },
                    { label: 'SECOND', pre: [[{ kind: 'module', source: 'MAA', port: 2, inPort: 2, tests: [[{ op: '==', left: v('connection_status'), right: { kind: 'string', value: 'disconnected' } }, { op: 'call', function: 'testit', args: [{ kind: 'string', value: 'dedede' }, v('temp_consigne')] }]], persistence: undefined, extractions: [] }, { kind: 'started', rule: 'FIRST', persistence: 'infinite' }]],
                      actions: [{ kind: 'subscribe', source: 'MSC', sourcePort: 1, inPort: 3, oneShot: true }, { kind: 'schema', schema: 'schemaCommande1', assignments: [{ parameter: 'consigne', value: v('temp_consigne') }] }],
                      post: [[{ kind: 'module', source: 'MSC', port: 1, inPort: 3, tests: [], persistence: undefined, extractions: [{ target: 'failure_data', path: [], value: v('failure') }, { target: 'temp_mess_type', path: [], value: { kind: 'string', value: 'commutation' } }] }]] },
                    { label: 'THIRD', pre: [[{ kind: 'endof', rule: 'SECOND', persistence: undefined }]], actions: [{ kind: 'notify', port: 1, assignments: [{ target: 'failure_message_type', path: [], value: v('temp_mess_type') }] }], post: [[{ kind: 'started', rule: 'THIRD', persistence: undefined }]] },
                    { label: 'FOURTH', pre: [[{ kind: 'endof', rule: 'SECOND', persistence: undefined }]], actions: [{ kind: 'compute', function: 'doit', args: [{ kind: 'string', value: '1.24' }, v('temp_consigne', 'k')] }, { kind: 'schema', schema: 'schemaCommande2', assignments: [{ parameter: 'consigne', value: v('temp_consigne') }] }], post: [[{ kind: 'endof', rule: 'FIRST', persistence: undefined }]] },
                    { label: 'RECEPTION', pre: [[{ kind: 'module', source: 'MAA', port: 0, inPort: 1, tests: [], persistence: undefined, extractions: [{ target: 'temp_message', path: [], value: v('message_received') }] }]],
                      actions: [{ kind: 'parameterize', module: 'MSC', settings: [{ port: 0, value: v('temp_message', 'value') }] }, { kind: 'resttime', module: 'MAA' }], post: [[{ kind: 'started', rule: 'RECEPTION', persistence: undefined }]] },
                ] }] },
            { name: 'GLB', eventIn: [{ name: 'gdyegdyegdyge', index: 0, type: str }], eventOut: [],
              functions: [{ name: 'mission', parameters: [{ name: 'consigne', type: A }], locals: [{ name: 'consigne_courante', type: A, default: v('consigne') }],
                rules: [{ label: 'SINGLE', pre: [[{ kind: 'elapsed', timeNs: 1e6, persistence: undefined }]],
                  actions: [{ kind: 'subscribe', source: 'SUP', sourcePort: 1, inPort: 0, oneShot: true }, { kind: 'supervisor', supervisor: 'SUP', function: 'action', assignments: [{ parameter: 'consigne', value: v('consigne_courante') }] }],
                  post: [[{ kind: 'module', source: 'SUP', port: 1, inPort: 0, tests: [[{ op: '==', left: v('gdyegdyegdyge'), right: { kind: 'string', value: 'commutation' } }]], persistence: undefined, extractions: [] }]] }] }] },
        ],
    };
}
