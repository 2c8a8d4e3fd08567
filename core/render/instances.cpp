#include "core/render/instances.h"

#include <epoxy/gl.h>

#include <algorithm>
#include <cstddef>

namespace sp::render {

void InstanceRecord::setModelViewProjection(const Eigen::Matrix4d& matrix) {
    const Eigen::Matrix4f rounded = matrix.cast<float>();
    std::copy(rounded.data(), rounded.data() + 16, modelViewProjection);
}

void InstanceRecord::setModel(const Eigen::Matrix4d& model, const Eigen::Matrix4d& modelToCamera) {
    for (int row = 0; row < 3; ++row)
        for (int column = 0; column < 4; ++column)
            modelRows[4 * row + column] = float(model(row, column));
    for (int column = 0; column < 4; ++column)
        depthRow[column] = float(modelToCamera(0, column));
}

void configureInstanceAttributes(unsigned vao) {
    auto floats = [&](unsigned location, std::size_t offset) {
        glEnableVertexArrayAttrib(vao, location);
        glVertexArrayAttribFormat(vao, location, 4, GL_FLOAT, GL_FALSE, GLuint(offset));
        glVertexArrayAttribBinding(vao, location, kInstanceBinding);
    };
    for (unsigned column = 0; column < 4; ++column)
        floats(kInstanceModelViewProjection + column,
               offsetof(InstanceRecord, modelViewProjection) + column * 4 * sizeof(float));
    for (unsigned row = 0; row < 3; ++row)
        floats(kInstanceModelRows + row, offsetof(InstanceRecord, modelRows) + row * 4 * sizeof(float));
    floats(kInstanceDepthRow, offsetof(InstanceRecord, depthRow));
    floats(kInstanceBaseColor, offsetof(InstanceRecord, baseColor));
    floats(kInstanceMaterial, offsetof(InstanceRecord, material));
    floats(kInstanceEmissive, offsetof(InstanceRecord, emissive));
    glEnableVertexArrayAttrib(vao, kInstanceIds);
    glVertexArrayAttribIFormat(vao, kInstanceIds, 4, GL_UNSIGNED_INT, GLuint(offsetof(InstanceRecord, ids)));
    glVertexArrayAttribBinding(vao, kInstanceIds, kInstanceBinding);
    glVertexArrayBindingDivisor(vao, kInstanceBinding, 1);
}

InstanceBuffer::InstanceBuffer() {
    glCreateBuffers(1, &buffer_);
}

InstanceBuffer::~InstanceBuffer() {
    glDeleteBuffers(1, &buffer_);
}

void InstanceBuffer::upload(const std::vector<InstanceRecord>& records) {
    glNamedBufferData(buffer_, GLsizeiptr(records.size() * sizeof(InstanceRecord)), records.data(),
                      GL_STREAM_DRAW);
}

void InstanceBuffer::bind(unsigned vao) const {
    glVertexArrayVertexBuffer(vao, kInstanceBinding, buffer_, 0, sizeof(InstanceRecord));
}

} // namespace sp::render
