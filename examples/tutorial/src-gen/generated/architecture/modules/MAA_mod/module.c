//          module source file
//          MODULE: MAA (asynchronous)
//          Libraries includes
#include <libmodule/libmodule.h>
#include <stdio.h>
#include <time.h>
#include <string.h>
#include "tools.h"
#include "SharedTypeC.h"
#include "SharedTypeE.h"
#include "SharedTypeA.h"

//from here you can make new imports or definitions
/*PROTECTED REGION ID(protect_additional_import_MAA) ENABLED START*/
#include <time.h>
/* MAA simulates a network link without user input (the report's version read commands with
   scanf): it follows a timed script, connect -> 4 messages -> disconnect, then ends its run. */
#define MAA_STEP_NS 250000000L /* one script step every 250 ms */
/*PROTECTED REGION END*/

MODULE_DESCRIPTION(/*PROTECTED REGION ID(protect_description_MAA) ENABLED START*/"test asynchronous module A for Cactal generation testing"/*PROTECTED REGION END*/);
MODULE_AUTHOR(/*PROTECTED REGION ID(protect_author_MAA) ENABLED START*/"Robin Passama (adapted for ContrACT Studio)"/*PROTECTED REGION END*/);

//Exchanges Management Variables
char controlevent[256] = "\0";
TypeC message_type_notification = { "\0", 0, { 0.0, 0.0, 0.0 } };
TypeE received_message = { { "\0", 0, { 0.0, 0.0, 0.0 } }, { "\0", 0 } };
char connection_status[256] = "\0";
TypeA param = { 22.12, 6.98, 897.34 };

// module name
char MODULE_NAME[] = "MAA";
//module priority
int MODULE_PRIORITY = 30;
// input data flows : example = { &Variable, PortReception, Size, "Name of emitter module"(can be unused by setting value to "---"), PortModuleEmetteur, Periodicity}
ModuleUse IUSE[] = { IUSE_TERM };

// output data flows : example = { &Variable, PortEmission, Size}
ModuleProduce IPRODUCE[] = { IPRODUCE_TERM };

//input event flows : example = { &Variable, PortReception, size, "module name" (can be unused by setting value to "---"), PortEmission, oneshot}
ModuleReact IREACT[] = { { &controlevent, 0, sizeof(char)*256, "---", 0, 0}, IREACT_TERM };

//output event flows : example = { &variable, PortEmission, size }
ModuleDetect IDETECT[] = { { &message_type_notification, 0, sizeof(TypeC)}, { &received_message, 1, sizeof(TypeE)}, { &connection_status, 2, sizeof(char)*256}, IDETECT_TERM };

// size of parameters that can be received in the request mailbox:
size_t PARAM_SIZE_IN[] = { sizeof(TypeA), PARAM_SIZE_TERM };

// size of parameters or events that can be sent in request mailboxes of other modules (user has to add sizes of sent param requests, if any):
size_t PARAM_SIZE_OUT[] = { /*PROTECTED REGION ID(protect_param_out_MAA) ENABLED START*/ /*PROTECTED REGION END*/PARAM_SIZE_TERM };

//global variables (the CSV log <MODULE>_<date>.csv is written by libmodule: add records with ContractLog())
RTIME productionTime, receptionTime;

//from here you can define new internal variables
/*PROTECTED REGION ID(protect_internal_vars_MAA) ENABLED START*/
int _connected = 0;
double _increment = 1.0;
int _step = 0;
/*PROTECTED REGION END*/

// Generic Prototypes (to be implemented by the user)
int _init_module(void);//==0 false, != 0 true
void _exit_module(void);
void _exec_module_state(int * stateindex);//state from 0 to x with x > 0, if stateindex is -1 at end of execution then run is finished
void _react_to_event(int receiverport, int senderport, char * sendermodule, RTIME * eventProductionTime, RTIME * eventReceptionTime);//to implement to react to some events
void _react_to_parameterizing(int parameterport, RTIME * productionTime, RTIME * receptionTime);//to implement to code reaction on parameterizing actions
//Specific prototypes (from here you can declare new internal functions)
/*PROTECTED REGION ID(protect_internal_functions_decl_MAA) ENABLED START*/
static void _wait_step(void);
static void _post_status(const char * status);
/*PROTECTED REGION END*/

int ModuleMain(int argc, const char * argv[])
{
    RequestMessage receivedMessage, registered;
    int subscription = 0;
    int end=0;
    int state=0;
    int interact,cycleRunning=0;
    (void)argc; (void)argv;
    memset(&receivedMessage, 0, sizeof(receivedMessage));
    memset(&registered, 0, sizeof(registered));

    if( _init_module() == 0 ){
        /* the init region refused to start (it returned 0): said, not left to read as a crash */
        fprintf(stderr, "%s: its init region returned 0 (false): the module does not start\n", MODULE_NAME);
        return(-1);
    }
    receivedMessage.Type=REQ_UNKNOWN;
    while(!end)
    {
        switch(receivedMessage.Type)
        {
            case REQ_UNKNOWN :
                if (cycleRunning && state != -1 && PendingRequests() > 0 && WaitForRequestUntil(&receivedMessage, 0) == 1)
                    break; //a request read with the one just handled (a STOP behind an UNSUB_EVENT) is handled before the run's next state
                if (cycleRunning){
                    if (state != -1){ //the execution has not been interrupted
                        //filling the received message with old START request information
                        receivedMessage.Type=REQ_START;
                        if ((registered.Param.Start.WantedAck&ACK_NOTHING) == 0)//do not try to copy module names if an ACK is not required
                            strcpy( receivedMessage.Param.Start.ModAck, registered.Param.Start.ModAck);
                        receivedMessage.Param.Start.WantedAck= registered.Param.Start.WantedAck;
                        receivedMessage.Param.Start.AckID = registered.Param.Start.AckID;
                    }
                    else { //the execution has been interrupted, waiting again
                        state = 0;
                        cycleRunning = 0;
                        //sending an acknowledge to the module that has started this module
                        if ((registered.Param.Start.WantedAck &ACK_STOPPED) != 0){
                            SendAck( registered.Param.Start.ModAck, registered.Param.Start.WantedAck, ACK_STOPPED, registered.Param.Start.AckID);
                        }
                        //reinitializing registered
                        registered.Type=REQ_UNKNOWN;
                        registered.Param.Start.WantedAck = ACK_NOTHING;
                        registered.Param.Start.AckID = -1;
                        //waiting a new request
                        if (WaitForRequest(&receivedMessage) == NULL) end = 1;
                        break;
                    }
                }
                else {
                    if (WaitForRequest(&receivedMessage) == NULL) end = 1;
                    break;
                }
                __attribute__((fallthrough)); //a START is resumed after a request was handled

            case REQ_START:
                if (cycleRunning == 0){//if execution cycle does not run
                    if ((receivedMessage.Param.Start.WantedAck&ACK_START) != 0) //if an ACK is required by the caller
                        SendAck( receivedMessage.Param.Start.ModAck, receivedMessage.Param.Start.WantedAck, ACK_START, receivedMessage.Param.Start.AckID);
                }
                if (subscription == 0){
                    SubscribeVariables();
                    SubscribeEvent();
                    subscription = 1;
                }
                interact = 0;
                cycleRunning = 1;
                while(!interact){
                    _exec_module_state(&state);
                    if(state==-1){//termination of the run
                        state = 0;
                        cycleRunning = 0;
                        interact = 1;
                        receivedMessage.Type=REQ_UNKNOWN;
                        if((receivedMessage.Param.Start.WantedAck&ACK_FINISHED) != 0) //if an ACK is required by the caller
                            SendAck( receivedMessage.Param.Start.ModAck, receivedMessage.Param.Start.WantedAck, ACK_FINISHED, receivedMessage.Param.Start.AckID);
                    }
                    if(cycleRunning){
                        //registering the previous request
                        registered.Type=receivedMessage.Type;
                        registered.Param.Start.WantedAck= receivedMessage.Param.Start.WantedAck;
                        registered.Param.Start.AckID = receivedMessage.Param.Start.AckID;
                        if ((registered.Param.Start.WantedAck&ACK_NOTHING) == 0)//do not try to copy module names if an ACK is not required
                            strcpy(registered.Param.Start.ModAck, receivedMessage.Param.Start.ModAck);

                        // polling on message to be reactive
                        if (LookForRequest(&receivedMessage) != NULL)
                            interact=1;
                    }
                }
                break;

            case REQ_STOP:
                if (cycleRunning) {
                    state = -1;
                    //sending an acknowledge
                    if ((receivedMessage.Param.Stop.WantedAck&ACK_STOPPED) != 0)//if an ACK is required
                        SendAck( receivedMessage.Param.Stop.ModAck, receivedMessage.Param.Stop.WantedAck, ACK_STOPPED, receivedMessage.Param.Stop.AckID);
                    registered.Param.Start.WantedAck = ACK_NOTHING; //the STOP request has been acknowledged
                }
                else {
                    state = 0;
                    if ((receivedMessage.Param.Stop.WantedAck&ACK_STOPPED) != 0){//if an ACK is required
                        SendAck( receivedMessage.Param.Stop.ModAck, receivedMessage.Param.Stop.WantedAck, ACK_NOTDONE, receivedMessage.Param.Stop.AckID);
                    }
                }
                receivedMessage.Type=REQ_UNKNOWN;
                break;

            case REQ_KILL:
                end = 1;
                if ((receivedMessage.Param.Kil.WantedAck&ACK_KILLED) != 0){//if an ACK is required
                    SendAck( receivedMessage.Param.Kil.ModAck, receivedMessage.Param.Kil.WantedAck, ACK_KILLED, receivedMessage.Param.Kil.AckID);
                }
                receivedMessage.Type=REQ_UNKNOWN;
                break;

            case REQ_EVENT:
                _react_to_event(GetEventId(&productionTime, &receptionTime), receivedMessage.Param.Event.sourcePort, &receivedMessage.Param.Event.sourceModule[0], &productionTime, &receptionTime);
                receivedMessage.Type=REQ_UNKNOWN;
                break;

            case REQ_SETPARAM:
                switch(receivedMessage.Param.SetParam.Port) {
                    case 0 :
                        GetDataFromSetParamRequest(&receivedMessage, &param, sizeof(TypeA), &productionTime, &receptionTime);
                        _react_to_parameterizing(0, &productionTime, &receptionTime);
                        break;
                    default:
                        printf("Unknown param port:%d\n", receivedMessage.Param.SetParam.Port);
                        break;
                }
                receivedMessage.Type=REQ_UNKNOWN;
                break;

            case REQ_SUBSCRIBE:
                SubscribeUser(receivedMessage.Param.Subscribe.SourcePort, receivedMessage.Param.Subscribe.TargetModule, receivedMessage.Param.Subscribe.TargetPort, receivedMessage.Param.Subscribe.Periodicity, receivedMessage.Param.Subscribe.isContextual);
                receivedMessage.Type=REQ_UNKNOWN;
                break;

            case REQ_UNSUBSCRIBE:
                UnsubscribeUser(receivedMessage.Param.Unsubscribe.SourcePort, receivedMessage.Param.Unsubscribe.TargetModule, receivedMessage.Param.Unsubscribe.TargetPort);
                receivedMessage.Type=REQ_UNKNOWN;
                break;

            case REQ_SUB_EVENT:
                SubscribeUserToEvent(receivedMessage.Param.SubscribeEvent.targetModule, receivedMessage.Param.SubscribeEvent.targetPort, receivedMessage.Param.SubscribeEvent.sourcePort, receivedMessage.Param.SubscribeEvent.mode);
                receivedMessage.Type=REQ_UNKNOWN;
                break;

            case REQ_UNSUB_EVENT:
                UnsubscribeUserToEvent(receivedMessage.Param.UnsubscribeEvent.targetModule, receivedMessage.Param.UnsubscribeEvent.targetPort, receivedMessage.Param.UnsubscribeEvent.sourcePort);
                receivedMessage.Type=REQ_UNKNOWN;
                break;

            case REQ_PURGE_MBX:
                PurgeData(NULL);
                receivedMessage.Type=REQ_UNKNOWN;
                break;

            default:
                receivedMessage.Type=REQ_UNKNOWN;
                break;
        }
    }
    UnsubscribeVariables();
    UnsubscribeEvent();
    _exit_module();
    return 0;
}

int _init_module(void){//==0 false, != 0 true
    /*PROTECTED REGION ID(protect_init_MAA) ENABLED START*/
    printf("initialization of MAA\n");
    _connected = 0;
    _step = 0;
    return 1;
    /*PROTECTED REGION END*/
}

void _exit_module(void){
    /*PROTECTED REGION ID(protect_exit_MAA) ENABLED START*/
    printf("termination of MAA\n");
    /*PROTECTED REGION END*/
}

void _exec_module_state(int * stateindex){//state from 0 to x with x > 0, if stateindex is -1 at end of execution then run is finished
    /*PROTECTED REGION ID(protect_exec_MAA) ENABLED START*/
    switch(*stateindex){
        case 0: //the script: one step per call, the module stays reactive between steps
            _wait_step();
            _step++;
            if (_step == 2 && _connected == 0){
                _post_status("connected");
                _connected = 1;
            }
            else if (_step >= 3 && _step <= 6 && _connected == 1){
                strcpy(received_message.message.message, "FUFU");
                received_message.message.messagetype = 1;
                received_message.message.value.i = received_message.message.value.i + _increment;
                received_message.message.value.j = received_message.message.value.j + _increment;
                received_message.message.value.k = received_message.message.value.k + _increment;
                strcpy(&received_message.data_.dataname[0], "0");
                received_message.data_.datavalue = 678;
                PostEvent(&received_message);
                printf("MAA : posting the whole message is done !\n");
                set_TypeC(&message_type_notification, &received_message.message);
                PostEvent(&message_type_notification);
                printf("MAA : posting the message type is done ! ");
                print_TypeC(&message_type_notification);
                printf("\n");
            }
            else if (_step == 8 && _connected == 1){
                _post_status("disconnected");
                _connected = 0;
                *stateindex = 1;
            }
            break;
        case 1:
            printf("MAA : state 1 => terminal state (the script replays at the next start)\n");
            _step = 0;
            *stateindex = -1;
            break;
        default:
            *stateindex = -1;
            break;
    }
    /*PROTECTED REGION END*/
}

void _react_to_event(int receiverport, int senderport, char * sendermodule, RTIME * eventProductionTime, RTIME * eventReceptionTime){
    (void)receiverport; (void)senderport; (void)sendermodule; (void)eventProductionTime; (void)eventReceptionTime;
    /*PROTECTED REGION ID(protect_event_MAA) ENABLED START*/
    switch(receiverport){
        case 0:
            printf("MAA : control event '%s' from %s\n", controlevent, strlen(sendermodule) ? sendermodule : "?");
            break;
        default:
            break;
    }
    /*PROTECTED REGION END*/
}

void _react_to_parameterizing(int parameterport, RTIME * productionTime, RTIME * receptionTime){
    (void)parameterport; (void)productionTime; (void)receptionTime;
    /*PROTECTED REGION ID(protect_param_MAA) ENABLED START*/
    if (parameterport == 0){
        printf("MAA : new param ");
        print_TypeA(&param);
        printf("\n");
        _increment = param.i != 0.0 ? param.i / 10.0 : 1.0;
    }
    /*PROTECTED REGION END*/
}

//Specific functions (from here you have to implement new internal functions declared before main)
/*PROTECTED REGION ID(protect_internal_functions_impl_MAA) ENABLED START*/
static void _wait_step(void){
    struct timespec step = { 0, MAA_STEP_NS };
    nanosleep(&step, NULL);
}

static void _post_status(const char * status){
    strcpy(connection_status, status);
    PostEvent(&connection_status[0]);
    printf("MAA : %s => event posted\n", status);
}
/*PROTECTED REGION END*/
