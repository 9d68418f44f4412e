package io.etherware.pendulum.components;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertSame;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.etherware.core.codec.MessageCodec;
import io.etherware.core.message.Contents;
import io.etherware.core.message.ContentsTypes;
import io.etherware.core.message.Criticality;
import io.etherware.core.message.Message;
import io.etherware.core.message.MessageFormatException;
import io.etherware.core.message.MessageId;
import io.etherware.core.message.Profile;
import io.etherware.core.message.QoS;
import io.etherware.pendulum.control.GainSet;
import io.etherware.pendulum.plant.PendulumState;
import io.etherware.pendulum.serial.BoardStatus;
import io.etherware.pendulum.serial.DspClient;
import java.nio.charset.StandardCharsets;
import java.util.Set;
import java.util.stream.Stream;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.params.ParameterizedTest;
import org.junit.jupiter.params.provider.MethodSource;

/** The components' messages and states on the wire: registered names and exact XML round trips. */
class PendulumContentsTest {

    static final MessageCodec CODEC = new MessageCodec(PendulumContents.register(new ContentsTypes()));
    static final DspProxyCounters COUNTERS = new DspProxyCounters(400, 399, 2, 1, 0, 3, 1, 0, -0.0125);

    static Stream<Contents> samples() {
        return Stream.of(
                new ReadAngles(17),
                new AnglesReading(17, 65535, -2048, 33, 15_015_000L, -3.141592653589793, 0.0506213),
                new SetTorque(17, -0.49999999999999994),
                new SetTorque(0, -0.0),
                new DspFault(17, DspFault.Kind.TIMEOUT, "no ANGLES reply to READ_ANGLES <after> 2 attempt(s) & more"),
                new StatusRequest(true),
                new DspProxyStatus(COUNTERS, new DspClient.Counters(1, 2, 3, 4, 5, 6),
                        new BoardStatus(1, 4_294_967_295L, 10, 2, 7, 1, 9, -0.5, 4096), null),
                new DspProxyStatus(COUNTERS, new DspClient.Counters(0, 0, 0, 0, 0, 0), null, "no STATUS reply"),
                COUNTERS);
    }

    static Message envelope(Contents contents) {
        return new Message(PendulumController.DEFAULT_PROFILE, DspProxy.DEFAULT_PROFILE, 1_767_225_600_015_000_000L,
                new QoS(Criticality.HIGH, 15_000_000L, 12_000_000L, 0), contents, new MessageId("plant-1", 3),
                new MessageId("ctrl-1", 2));
    }

    static Message roundTrip(MessageCodec codec, Message message) {
        return codec.decode(codec.encode(message));
    }

    @ParameterizedTest
    @MethodSource("samples")
    void shouldRoundTripExactlyThroughTheXmlCodec(Contents contents) {
        Message message = envelope(contents);
        assertEquals(message, roundTrip(CODEC, message));
    }

    @Test
    void shouldRoundTripTheStateOfARunningControllerAndRestoreItIntoANewInstance() {
        try (LockStepLoop loop = new LockStepLoop(new PendulumState(0.0, 0.0, 0.05, 0.0), GainSet.v1Soft(LockStepLoop.PARAMETERS))) {
            loop.cycles(40);
            ControllerState state = loop.controllerState();
            assertTrue(state.control().estimator().primed());

            Message shipped = roundTrip(CODEC, envelope(state));
            assertEquals(state, shipped.contents());

            // What a migration does on the other node: a new instance restored from the XML state.
            PendulumController arrived = new PendulumController(ControllerConfig.defaults(),
                    GainSet.v1Soft(LockStepLoop.PARAMETERS), ControlListener.NONE);
            arrived.restore((ControllerState) shipped.contents());
            assertEquals(state, arrived.snapshot());
        }
    }

    @Test
    void shouldWriteTheRegisteredNamesNotJavaClassNames() {
        String xml = CODEC.encodeToString(envelope(new AnglesReading(1, 2, 3, 4, 5, 0.5, -0.25)));
        assertTrue(xml.contains("<contents type=\"pendulum.angles\">"), xml);
        assertTrue(xml.contains("<theta2Rad>-0.25</theta2Rad>"), xml);
        assertTrue(!xml.contains("io.etherware"), xml);
    }

    @Test
    void shouldRegisterStableNamesIdempotently() {
        ContentsTypes types = new ContentsTypes();
        assertSame(types, PendulumContents.register(types));
        PendulumContents.register(types);
        assertEquals(ReadAngles.class, types.typeOf("pendulum.read-angles"));
        assertEquals(AnglesReading.class, types.typeOf("pendulum.angles"));
        assertEquals(SetTorque.class, types.typeOf("pendulum.set-torque"));
        assertEquals(DspFault.class, types.typeOf("pendulum.dsp-fault"));
        assertEquals(StatusRequest.class, types.typeOf("pendulum.status-request"));
        assertEquals(DspProxyStatus.class, types.typeOf("pendulum.dsp-status"));
        assertEquals(DspProxyCounters.class, types.typeOf("pendulum.dsp-proxy-counters"));
        assertEquals(ControllerState.class, types.typeOf("pendulum.controller-state"));
        Set<String> ours = Set.copyOf(types.names().stream().filter(n -> n.startsWith("pendulum.")).toList());
        assertEquals(8, ours.size(), ours::toString);
    }

    @Test
    void shouldRefuseAMessageOfAnUnregisteredRegistry() {
        ContentsTypes types = PendulumContents.register(new ContentsTypes());
        MessageCodec codec = MessageCodec.builder().contentsTypes(types).build();
        Message message = envelope(new SetTorque(3, 0.2));
        assertEquals(message, roundTrip(codec, message));
        MessageCodec unaware = MessageCodec.builder().contentsTypes(new ContentsTypes()).build();
        byte[] document = codec.encode(message);
        MessageFormatException error = assertThrows(MessageFormatException.class, () -> unaware.decode(document));
        assertTrue(error.getMessage().contains("pendulum.set-torque"), error.getMessage());
    }

    @Test
    void shouldRejectANonFiniteAngleFromAPeerWithAnErrorNamingTheType() {
        String xml = CODEC.encodeToString(envelope(new AnglesReading(1, 2, 3, 4, 5, 0.5, -0.25)))
                .replace("<theta2Rad>-0.25</theta2Rad>", "<theta2Rad>NaN</theta2Rad>");
        MessageFormatException error = assertThrows(MessageFormatException.class,
                () -> CODEC.decode(xml.getBytes(StandardCharsets.UTF_8)));
        assertTrue(error.getMessage().contains("pendulum.angles"), error.getMessage());
    }

    @Test
    void shouldRejectAStateOfAnotherTypeOrSchemaWhenRestoring() {
        PendulumController controller = new PendulumController(ControllerConfig.defaults(),
                GainSet.v2Tight(LockStepLoop.PARAMETERS), ControlListener.NONE);
        assertThrows(IllegalArgumentException.class, () -> controller.restore(COUNTERS));
        assertThrows(IllegalArgumentException.class, () -> controller.restore(null));
        assertEquals(ControllerState.SCHEMA_VERSION, controller.snapshot().schemaVersion());
    }
}
