package io.etherware.services.management;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertInstanceOf;
import static org.junit.jupiter.api.Assertions.assertThrows;

import io.etherware.core.codec.MessageCodec;
import io.etherware.core.message.Contents;
import io.etherware.core.message.Message;
import io.etherware.core.message.MessageId;
import io.etherware.core.message.Profile;
import io.etherware.core.message.Text;
import java.nio.file.Path;
import java.util.List;
import org.junit.jupiter.api.Test;

/** The management contents cross nodes: registered, and exact through the XML codec. */
class ManagementContentsTest {

    private static final Profile TARGET = Profile.parse("controller[car=1]");

    private static Message carrying(Contents contents) {
        return new Message(Management.profileOf("plant-1"), Profile.parse("etherware.node[id=console]"), 1_000L,
                Management.REQUEST_QOS, contents, new MessageId("console", 3), null);
    }

    @Test
    void shouldRoundTripEveryManagementContentsThroughTheCodecWhenFieldsAreNullOrSet() {
        var types = new io.etherware.core.message.ContentsTypes();
        Management.registerContents(types);
        var codec = new MessageCodec(types);
        for (Contents contents : List.of(
                UpgradeRequest.of(TARGET, Implementation.ofClass("com.example.ControllerV2")),
                UpgradeRequest.of(TARGET, Implementation.fromJar(Path.of("/opt/upgrades/c.jar"), "com.example.C")
                        .withConfiguration("k1=-12.1, k2=95.3 <&>")),
                new UpgradeResult(TARGET, "com.example.V1", "com.example.V2", UpgradeResult.CLASSPATH, 2, 51_000,
                        9_700, 23_400, 120_000),
                new UpgradeResult(TARGET, "a.B", "a.C", "/opt/upgrades/c.jar", -1, 1, 2, -1, 3),
                new ManagementFailure("upgrade", TARGET, ManagementFailure.Reason.ROLLED_BACK,
                        "restore threw: java.lang.IllegalStateException: schema 1"))) {
            Message message = carrying(contents);
            assertEquals(message, codec.decode(codec.encode(message)), contents.getClass().getSimpleName());
        }
    }

    @Test
    void shouldTurnAFailureAnswerIntoAManagementExceptionAndRefuseAnythingElse() {
        var failure = new ManagementFailure("upgrade", TARGET, ManagementFailure.Reason.CODE_NOT_ALLOWED, "no");
        var thrown = assertThrows(ManagementException.class, () -> Management.upgradeResultOf(carrying(failure)));
        assertEquals(failure, thrown.failure());
        assertEquals("upgrade of 'controller[car=1]' failed (CODE_NOT_ALLOWED): no", thrown.getMessage());
        assertInstanceOf(IllegalStateException.class,
                assertThrows(RuntimeException.class, () -> Management.upgradeResultOf(carrying(new Text("?")))));
    }

    @Test
    void shouldNameTheManagementServiceOfANode() {
        assertEquals(Profile.parse("etherware.management[node=plant-1]"), Management.profileOf("plant-1"));
    }
}
