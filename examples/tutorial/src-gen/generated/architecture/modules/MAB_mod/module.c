//          module source file
//          MODULE: MAB (asynchronous)
//          Libraries includes
#include <libmodule/libmodule.h>
#include <stdio.h>
#include <time.h>
#include <string.h>
#include "tools.h"
#include "SharedTypeC.h"

//from here you can make new imports or definitions
/*PROTECTED REGION ID(protect_additional_import_MAB) ENABLED START*/
//TODO
/*PROTECTED REGION END*/

MODULE_DESCRIPTION(/*PROTECTED REGION ID(protect_description_MAB) ENABLED START*/"asynchronous module MAB"/*PROTECTED REGION END*/);
MODULE_AUTHOR(/*PROTECTED REGION ID(protect_author_MAB) ENABLED START*/"TODO"/*PROTECTED REGION END*/);

//Exchanges Management Variables
TypeC message_type_notification = { "\0", 0, { 0.0, 0.0, 0.0 } };

// module name
char MODULE_NAME[] = "MAB";
//module priority
int MODULE_PRIORITY = 30;
// input data flows : example = { &Variable, PortReception, Size, "Name of emitter module"(can be unused by setting value to "---"), PortModuleEmetteur, Periodicity}
ModuleUse IUSE[] = { IUSE_TERM };

// output data flows : example = { &Variable, PortEmission, Size}
ModuleProduce IPRODUCE[] = { IPRODUCE_TERM };

//input event flows : example = { &Variable, PortReception, size, "module name" (can be unused by setting value to "---"), PortEmission, oneshot}
ModuleReact IREACT[] = { { &message_type_notification, 0, sizeof(TypeC), "---", 0, 0}, IREACT_TERM };

//output event flows : example = { &variable, PortEmission, size }
ModuleDetect IDETECT[] = { IDETECT_TERM };

// size of parameters that can be received in the request mailbox:
size_t PARAM_SIZE_IN[] = { PARAM_SIZE_TERM };

// size of parameters or events that can be sent in request mailboxes of other modules (user has to add sizes of sent param requests, if any):
size_t PARAM_SIZE_OUT[] = { /*PROTECTED REGION ID(protect_param_out_MAB) ENABLED START*/ /*PROTECTED REGION END*/PARAM_SIZE_TERM };

//global variables (the CSV log <MODULE>_<date>.csv is written by libmodule: add records with ContractLog())
RTIME productionTime, receptionTime;

//from here you can define new internal variables
/*PROTECTED REGION ID(protect_internal_vars_MAB) ENABLED START*/
//TODO
/*PROTECTED REGION END*/

// Generic Prototypes (to be implemented by the user)
int _init_module(void);//==0 false, != 0 true
void _exit_module(void);
void _exec_module_state(int * stateindex);//state from 0 to x with x > 0, if stateindex is -1 at end of execution then run is finished
void _react_to_event(int receiverport, int senderport, char * sendermodule, RTIME * eventProductionTime, RTIME * eventReceptionTime);//to implement to react to some events
//Specific prototypes (from here you can declare new internal functions)
/*PROTECTED REGION ID(protect_internal_functions_decl_MAB) ENABLED START*/
//TODO
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
    /*PROTECTED REGION ID(protect_init_MAB) ENABLED START*/
    //TODO
    return 1;
    /*PROTECTED REGION END*/
}

void _exit_module(void){
    /*PROTECTED REGION ID(protect_exit_MAB) ENABLED START*/
    //TODO
    /*PROTECTED REGION END*/
}

void _exec_module_state(int * stateindex){//state from 0 to x with x > 0, if stateindex is -1 at end of execution then run is finished
    /*PROTECTED REGION ID(protect_exec_MAB) ENABLED START*/
    //MAB only reacts to events: its run ends at once, the events keep coming
    *stateindex = -1;
    /*PROTECTED REGION END*/
}

void _react_to_event(int receiverport, int senderport, char * sendermodule, RTIME * eventProductionTime, RTIME * eventReceptionTime){
    (void)receiverport; (void)senderport; (void)sendermodule; (void)eventProductionTime; (void)eventReceptionTime;
    /*PROTECTED REGION ID(protect_event_MAB) ENABLED START*/
    if (receiverport == 0){
        printf("MAB : received message type notification ");
        print_TypeC(&message_type_notification);
        printf("\n");
    }
    /*PROTECTED REGION END*/
}

//Specific functions (from here you have to implement new internal functions declared before main)
/*PROTECTED REGION ID(protect_internal_functions_impl_MAB) ENABLED START*/
//TODO
/*PROTECTED REGION END*/
