/**
 * Recording the messages that pass chosen profiles of a node to a file, and replaying them into a
 * node later, as rosbag does for ROS topics: {@link io.etherware.services.recording.Recorder},
 * {@link io.etherware.services.recording.Recording}. The file format is in
 * {@code etherware-services/RECORDING.md}.
 *
 * <pre>{@code
 * try (Recorder recorder = Recorder.start(node, Path.of("run.ewrec"), List.of(Profile.parse("dspProxy")))) {
 *     ... // the messages sent to the DSPProxy are written as they pass
 * }
 * Recording recording = Recording.read(Path.of("run.ewrec"), otherNode.contentsTypes());
 * recording.replay(otherNode, 1.0); // the same messages, at the same pace
 * }</pre>
 */
package io.etherware.services.recording;
